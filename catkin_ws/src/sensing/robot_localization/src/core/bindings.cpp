// robot_localization._ekf_core: the EKF core for the Python node (pybind11). The state and
// covariance are exposed as NumPy views of the core's own memory (writable in place).
#include <pybind11/eigen.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "robot_localization/ekf.h"

namespace py = pybind11;
using robot_localization::Ekf;
using robot_localization::StateMatrix;
using robot_localization::StateVector;

PYBIND11_MODULE(_ekf_core, m)
{
  m.doc() = "robot_localization's EKF core (C++): 15-D state, omnidirectional model";
  m.attr("STATE_SIZE") = robot_localization::STATE_SIZE;
  m.attr("MIN_VARIANCE") = robot_localization::MIN_VARIANCE;
  m.def("normalize_angle", &robot_localization::normalizeAngle);
  m.def("sanitize_covariance", &robot_localization::sanitizeCovariance,
        "negative variances -> absolute value, tiny ones -> MIN_VARIANCE");
  py::class_<Ekf>(m, "Ekf")
      .def(py::init<>())
      .def_property(
          "x", [](Ekf& e) -> Eigen::Ref<StateVector> { return e.state(); },
          [](Ekf& e, const StateVector& v) { e.state() = v; }, py::return_value_policy::reference_internal)
      .def_property(
          "P", [](Ekf& e) -> Eigen::Ref<StateMatrix> { return e.covariance(); },
          [](Ekf& e, const StateMatrix& v) { e.covariance() = v; }, py::return_value_policy::reference_internal)
      .def_property("Q", &Ekf::processNoiseCovariance, &Ekf::setProcessNoiseCovariance)
      .def_property("P0", &Ekf::initialCovariance, &Ekf::setInitialCovariance)
      .def_readwrite("initialized", &Ekf::initialized)
      .def_readwrite("has_time", &Ekf::hasTime)
      .def_readwrite("time", &Ekf::lastTime)
      .def_readwrite("rejected", &Ekf::rejected)
      .def_readwrite("nan_detected", &Ekf::nanDetected)
      .def("reset", py::overload_cast<>(&Ekf::reset))
      .def("reset", py::overload_cast<const StateVector&>(&Ekf::reset))
      .def("transfer", &Ekf::transfer)
      .def("predict", &Ekf::predict)
      .def("process", &Ekf::process, py::arg("time"), py::arg("z"), py::arg("covariance"), py::arg("indices"),
           py::arg("threshold") = std::numeric_limits<double>::infinity())
      .def("correct", &Ekf::correct, py::arg("z"), py::arg("covariance"), py::arg("indices"),
           py::arg("threshold") = std::numeric_limits<double>::infinity());
}
