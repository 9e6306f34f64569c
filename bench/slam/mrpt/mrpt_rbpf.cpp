// bench/slam candidate: MRPT 2.5's RBPF grid-map SLAM (mrpt::slam::CMetricMapBuilderRBPF, optimal
// proposal) on the same scans and odometry as our core. Reads the text dump written by
// bench/slam/run --mrpt (header: beams angle_min angle_increment max_range laser_x laser_y;
// then per scan: stamp odom_x odom_y odom_yaw ranges...), writes "stamp x y yaw" of the
// current best base pose after every scan, and the wall and CPU time of the processing on stderr.
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/poses/CPose3DPDF.h>
#include <mrpt/slam/CMetricMapBuilderRBPF.h>

#include <chrono>
#include <ctime>
#include <cmath>
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: mrpt_rbpf <config.ini> <scans.txt>\n";
    return 2;
  }
  std::ifstream ini(argv[1]);
  std::stringstream ini_text;
  ini_text << ini.rdbuf();
  mrpt::config::CConfigFileMemory cfg(ini_text.str());
  mrpt::slam::CMetricMapBuilderRBPF::TConstructionOptions opts;
  opts.loadFromConfigFile(cfg, "MappingApplication");
  opts.verbosity_level = mrpt::system::LVL_ERROR;
  mrpt::slam::CMetricMapBuilderRBPF builder(opts);
  builder.initialize();

  std::ifstream in(argv[2]);
  size_t beams;
  double angle_min, angle_inc, max_range, lx, ly;
  in >> beams >> angle_min >> angle_inc >> max_range >> lx >> ly;
  std::vector<float> ranges(beams);
  bool first = true;
  mrpt::poses::CPose2D last;
  double busy = 0.0, cpu = 0.0;
  double stamp, ox, oy, oth;
  mrpt::obs::CActionRobotMovement2D::TMotionModelOptions motion;
  motion.modelSelection = mrpt::obs::CActionRobotMovement2D::mmGaussian;
  while (in >> stamp >> ox >> oy >> oth) {
    for (size_t i = 0; i < beams; ++i) in >> ranges[i];
    mrpt::poses::CPose2D odom(ox, oy, oth);
    auto t0 = std::chrono::steady_clock::now();
    std::clock_t c0 = std::clock();
    auto scan = mrpt::obs::CObservation2DRangeScan::Create();
    scan->aperture = static_cast<float>(angle_inc * (beams - 1));
    scan->rightToLeft = true;
    scan->maxRange = static_cast<float>(max_range);
    scan->sensorPose = mrpt::poses::CPose3D(lx, ly, 0, 0, 0, 0);
    scan->resizeScan(beams);
    for (size_t i = 0; i < beams; ++i) {
      float r = ranges[i];
      bool ok = std::isfinite(r) && r > 0.0f && r < max_range;
      scan->setScanRange(i, ok ? r : 0.0f);
      scan->setScanRangeValidity(i, ok);
    }
    mrpt::obs::CSensoryFrame sf;
    sf.insert(scan);
    mrpt::obs::CActionCollection acts;
    mrpt::obs::CActionRobotMovement2D act;
    act.computeFromOdometry(first ? mrpt::poses::CPose2D() : odom - last, motion);
    acts.insert(act);
    builder.processActionObservation(acts, sf);
    busy += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    cpu += static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
    last = odom;
    first = false;
    auto est = builder.getCurrentPoseEstimation()->getMeanVal();
    std::cout << stamp << ' ' << est.x() << ' ' << est.y() << ' ' << est.yaw() << '\n';
  }
  std::cerr << "mrpt_rbpf: processing time " << busy << " s, cpu " << cpu << " s\n";
  return 0;
}
