// rosserial_server (re-implementation): message and service look-ups through an embedded
// Python interpreter (roslib.message), cached per type.
#include <Python.h>

#include "rosserial_server/msg_lookup.h"

#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace rosserial_server
{
namespace
{
std::mutex g_mutex;
std::map<std::string, MsgInfo> g_messages;
std::map<std::string, ServiceInfo> g_services;

void ensurePython()
{
  if (!Py_IsInitialized())
  {
    Py_InitializeEx(0);   // no signal handlers: roscpp keeps SIGINT
    PyEval_SaveThread();  // release the GIL; every look-up takes it with PyGILState_Ensure
  }
}

class Gil
{
public:
  Gil() : state_(PyGILState_Ensure()) {}
  ~Gil() { PyGILState_Release(state_); }

private:
  PyGILState_STATE state_;
};

// PyObject holder
class Ref
{
public:
  explicit Ref(PyObject* o = nullptr) : o_(o) {}
  ~Ref() { Py_XDECREF(o_); }
  Ref(const Ref&) = delete;
  Ref& operator=(const Ref&) = delete;
  PyObject* get() const { return o_; }
  explicit operator bool() const { return o_ != nullptr; }

private:
  PyObject* o_;
};

std::string pyError()
{
  PyObject *type, *value, *tb;
  PyErr_Fetch(&type, &value, &tb);
  std::string text = "unknown Python error";
  if (value)
  {
    Ref s(PyObject_Str(value));
    if (s && PyUnicode_Check(s.get()))
      text = PyUnicode_AsUTF8(s.get());
  }
  Py_XDECREF(type);
  Py_XDECREF(value);
  Py_XDECREF(tb);
  return text;
}

std::string strAttr(PyObject* o, const char* name, const std::string& type)
{
  Ref a(PyObject_GetAttrString(o, name));
  if (!a || !PyUnicode_Check(a.get()))
    throw std::runtime_error("type " + type + " has no " + name + ": " + pyError());
  return PyUnicode_AsUTF8(a.get());
}

// roslib.message.get_<kind>_class(type) -> new reference, or throws
PyObject* loadClass(const char* getter, const std::string& type)
{
  Ref mod(PyImport_ImportModule("roslib.message"));
  if (!mod)
    throw std::runtime_error("cannot import roslib.message: " + pyError());
  Ref fn(PyObject_GetAttrString(mod.get(), getter));
  if (!fn)
    throw std::runtime_error(std::string("roslib.message has no ") + getter);
  Ref cls(PyObject_CallFunction(fn.get(), "s", type.c_str()));
  if (!cls || cls.get() == Py_None)
  {
    std::string why = cls ? "" : ": " + pyError();
    throw std::runtime_error("cannot load the type " + type + " (is its package built and the workspace sourced?)" +
                             why);
  }
  PyObject* out = cls.get();
  Py_INCREF(out);
  return out;
}
}  // namespace

const MsgInfo lookupMessage(const std::string& message_type)
{
  std::lock_guard<std::mutex> lock(g_mutex);
  auto it = g_messages.find(message_type);
  if (it != g_messages.end())
    return it->second;
  ensurePython();
  Gil gil;
  Ref cls(loadClass("get_message_class", message_type));
  MsgInfo info;
  info.md5sum = strAttr(cls.get(), "_md5sum", message_type);
  info.full_text = strAttr(cls.get(), "_full_text", message_type);
  g_messages[message_type] = info;
  return info;
}

const ServiceInfo lookupService(const std::string& service_type)
{
  std::lock_guard<std::mutex> lock(g_mutex);
  auto it = g_services.find(service_type);
  if (it != g_services.end())
    return it->second;
  ensurePython();
  Gil gil;
  Ref cls(loadClass("get_service_class", service_type));
  ServiceInfo info;
  info.md5sum = strAttr(cls.get(), "_md5sum", service_type);
  Ref req(PyObject_GetAttrString(cls.get(), "_request_class"));
  Ref res(PyObject_GetAttrString(cls.get(), "_response_class"));
  if (!req || !res)
    throw std::runtime_error("service type " + service_type + " has no request/response class");
  info.request_md5sum = strAttr(req.get(), "_md5sum", service_type + "Request");
  info.response_md5sum = strAttr(res.get(), "_md5sum", service_type + "Response");
  g_services[service_type] = info;
  return info;
}

void warmUpLookups()
{
  std::thread(
      []
      {
        try
        {
          lookupMessage("std_msgs/Time");
        }
        catch (const std::exception&)
        {
        }
      })
      .detach();
}

}  // namespace rosserial_server
