// FillAngleScript on embedded CPython (pybind11), or a stub that explains its absence when the
// build has no Python (TRANCHE_PYTHON off, or pybind11/Python headers not found).
#include <cmath>

#include "base/input_file.h"
#include "geometry/fillangle/fill_angle.h"

#if TRANCHE_HAVE_PYTHON
#include <fmt/format.h>
#include <pybind11/embed.h>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "base/temp_files.h"
#include "geometry/fillangle/call_watch.h"
#endif

namespace tranche::geo {

namespace {

std::string where_island(const FillAngleContext& c) {
  return "layer " + std::to_string(c.layer_index) + ", island " + std::to_string(c.island_index);
}

Result<std::string> read_script(const std::string& path) { return read_input(path, kScriptInput); }

}  // namespace

#if TRANCHE_HAVE_PYTHON

namespace py = pybind11;

namespace {

// A deadline on CPython's start. Out of memory, the start can spin for good inside its import
// machinery (seen under ulimit -v 30 MB: a run that never ended), and a sitecustomize module
// that never returns holds it as well. Past the deadline the run ends with `message`, as for a
// call that cannot be interrupted (CallWatch); nothing was written yet.
class StartDeadline {
 public:
  StartDeadline(double seconds, std::string message)
      : message_(std::move(message)), thread_([this, seconds] {
          std::unique_lock lock(mu_);
          if (cv_.wait_for(lock, std::chrono::duration<double>(seconds), [&] { return done_; })) return;
          std::fprintf(stderr, "error: %s\n", message_.c_str());
          temp_files::unlink_all();
          ::_exit(1);
        }) {}
  ~StartDeadline() {
    {
      std::lock_guard lock(mu_);
      done_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }
  StartDeadline(const StartDeadline&) = delete;
  StartDeadline& operator=(const StartDeadline&) = delete;

 private:
  std::string message_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false;
  std::thread thread_;  // last: started once the rest is made
};

// The start's deadline: the script's timeout, but never under 10 s (a start takes ~0.05 s).
constexpr double kMinStartDeadlineS = 10;

// One interpreter per process, started on first use and never finalized (finalizing and
// restarting CPython is unreliable). The GIL is released after start-up so that any thread can
// take it for a call. A watchdog thread that cannot start throws std::system_error (out of memory).
void ensure_interpreter(const std::string& path, double timeout_s) {
  static std::once_flag once;
  std::call_once(once, [&] {
    if (Py_IsInitialized()) return;
    const double deadline_s = std::max(timeout_s, kMinStartDeadlineS);
    StartDeadline deadline(deadline_s,
                           fmt::format("{}: Python did not start within {:g} s (too little memory for it, see "
                                       "--max-memory and ulimit -v, or a sitecustomize module that does not "
                                       "return); tranche stopped, nothing was written",
                                       path, deadline_s));
    py::initialize_interpreter(/*init_signal_handlers=*/false, 0, nullptr, /*add_program_dir_to_path=*/false);
    PyEval_SaveThread();
  });
}

std::string trim_newlines(std::string s) {
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

// "Traceback (most recent call last): ... ValueError: boom", as Python prints it.
std::string format_traceback(py::error_already_set& e) {
  try {
    py::list lines =
        py::module_::import("traceback").attr("format_exception")(e.type(), e.value(), e.trace());
    std::string out;
    for (py::handle l : lines) out += l.cast<std::string>();
    return trim_newlines(out);
  } catch (const py::error_already_set&) {
    return e.what();
  }
}

// path:line of the innermost traceback frame that is in the script, or just the path.
std::string script_location(py::error_already_set& e, const std::string& path) {
  std::string where = path;
  try {
    if (!e.trace()) return where;
    py::list frames = py::module_::import("traceback").attr("extract_tb")(e.trace());
    for (py::handle f : frames)
      if (f.attr("filename").cast<std::string>() == path)
        where = path + ":" + std::to_string(f.attr("lineno").cast<long>());
  } catch (const py::error_already_set&) {
  }
  return where;
}

std::string short_repr(py::handle o) {
  try {
    std::string r = py::repr(o).cast<std::string>();
    if (r.size() > 60) r.resize(57), r.append("...");
    return r;
  } catch (const py::error_already_set&) {
    return std::string(1, '?');
  }
}

// The ring without vertices that lie on the line through their neighbours to within half a
// micrometre: a mesh's side triangles leave such vertices in the middle of straight edges
// (exactly collinear ones are already gone), and scripts look at corners and edges.
Ring without_straight_vertices(const Ring& ring) {
  constexpr double kTol = 500;  // units (nm)
  Ring out;
  for (const Point& p : ring) {
    out.push_back(p);
    while (out.size() >= 3) {
      const Point &a = out[out.size() - 3], &b = out[out.size() - 2], &c = out.back();
      double dx = double(c.X - a.X), dy = double(c.Y - a.Y), len = std::hypot(dx, dy);
      double cross = std::abs(dx * double(b.Y - a.Y) - dy * double(b.X - a.X));
      bool between = (double(b.X - a.X) * dx + double(b.Y - a.Y) * dy) > 0 &&
                     (double(c.X - b.X) * dx + double(c.Y - b.Y) * dy) > 0;
      if (len == 0 || !between || cross > kTol * len) break;
      out.erase(out.end() - 2);
    }
  }
  // The seam: the first and last vertices against their wrapped neighbours.
  for (bool changed = true; changed && out.size() > 3;) {
    changed = false;
    for (size_t k : {size_t(0), out.size() - 1}) {
      const Point& a = out[(k + out.size() - 1) % out.size()];
      const Point& b = out[k];
      const Point& c = out[(k + 1) % out.size()];
      double dx = double(c.X - a.X), dy = double(c.Y - a.Y), len = std::hypot(dx, dy);
      double cross = std::abs(dx * double(b.Y - a.Y) - dy * double(b.X - a.X));
      bool between = (double(b.X - a.X) * dx + double(b.Y - a.Y) * dy) > 0 &&
                     (double(c.X - b.X) * dx + double(c.Y - b.Y) * dy) > 0;
      if (len > 0 && between && cross <= kTol * len) {
        out.erase(out.begin() + static_cast<std::ptrdiff_t>(k));
        changed = true;
        break;
      }
    }
  }
  return out.size() >= 3 ? out : ring;
}

py::list ring_to_list(const Ring& ring) {
  py::list l;
  for (const Point& p : without_straight_vertices(ring)) l.append(py::make_tuple(to_mm(p.X), to_mm(p.Y)));
  return l;
}

// "file:line:col: syntax error: ..." with the line and a caret, from Python's SyntaxError.
Error syntax_error(py::error_already_set& e, const std::string& path) {
  py::object v = e.value();
  auto get_int = [&](const char* name) -> long {
    py::object a = v.attr(name);
    return a.is_none() ? 0 : a.cast<long>();
  };
  long line = get_int("lineno"), col = get_int("offset");
  std::string msg = "syntax error: " + py::str(v.attr("msg")).cast<std::string>();
  if (py::object text = v.attr("text"); !text.is_none()) {
    std::string t = trim_newlines(text.cast<std::string>());
    msg += "\n    " + t;
    if (col > 0) msg += "\n    " + std::string(static_cast<size_t>(col - 1), ' ') + "^";
  }
  return Error{path + ":" + std::to_string(line) + (col > 0 ? ":" + std::to_string(col) : ""), msg};
}

std::string seconds_text(double s) { return fmt::format("{:g} s", s); }

// What the watchdog prints if a call cannot be interrupted (CallWatch ends the process).
std::string stuck_message(const std::string& path, const std::string& what, double timeout_s) {
  return fmt::format("{}: {} did not return within {} (--script-timeout) and could not be interrupted (it is "
                     "waiting inside C code, e.g. time.sleep); tranche stopped, nothing was written",
                     path, what, seconds_text(timeout_s));
}

}  // namespace

struct FillAngleScript::Impl {
  py::object globals, fn, namespace_type;
  std::unique_ptr<CallWatch> watch;
  // Never throws: it may run while an error is on its way out (out of memory included), and an
  // exception out of it would end the process.
  ~Impl() {
    try {
      py::gil_scoped_acquire gil;
      // Flush what the script printed: the interpreter is never finalized, which would do it.
      try {
        py::module_ sys = py::module_::import("sys");
        sys.attr("stdout").attr("flush")();
        sys.attr("stderr").attr("flush")();
      } catch (...) {
      }
      fn = py::object();
      namespace_type = py::object();
      globals = py::object();
    } catch (...) {  // no GIL to be had: the objects are left to the interpreter
      fn.release();
      namespace_type.release();
      globals.release();
    }
  }
};

bool FillAngleScript::available() { return true; }

Result<std::unique_ptr<FillAngleScript>> FillAngleScript::load(const std::string& path, double timeout_s) {
  auto source = read_script(path);
  if (!source) return source.error();
  try {
    ensure_interpreter(path, timeout_s);
  } catch (const std::system_error&) {  // the deadline's thread: out of memory, said by the callers
    throw;
  } catch (const std::runtime_error& e) {  // pybind11's: CPython's start failed (std::bad_alloc passes)
    return Error{path, fmt::format("cannot start Python for the script: {} (too little memory for it, see "
                                   "--max-memory and ulimit -v, or a broken Python installation)",
                                   e.what())};
  }
  py::gil_scoped_acquire gil;
  auto impl = std::make_unique<Impl>();
  impl->watch = std::make_unique<CallWatch>(timeout_s);
  try {
    // The script's folder first on sys.path, so that it can import modules beside it.
    std::string dir = std::filesystem::absolute(path).parent_path().string();
    py::list sys_path = py::module_::import("sys").attr("path");
    if (!sys_path.contains(dir)) sys_path.insert(0, dir);

    py::dict globals;
    globals["__name__"] = "__fill_angle_script__";
    globals["__file__"] = path;
    globals["__builtins__"] = py::module_::import("builtins");
    py::object code;
    try {
      code = py::module_::import("builtins").attr("compile")(py::bytes(*source), path, "exec");
    } catch (py::error_already_set& e) {
      if (!e.matches(PyExc_SyntaxError)) throw;
      return syntax_error(e, path);
    }
    impl->watch->arm(stuck_message(path, "the script's top level", timeout_s));
    try {
      py::module_::import("builtins").attr("exec")(code, globals);
    } catch (py::error_already_set& e) {
      if (impl->watch->disarm())
        return Error{path, fmt::format("the script's top level took longer than {} (--script-timeout) and was "
                                       "stopped; make it faster, or raise --script-timeout",
                                       seconds_text(timeout_s))};
      return Error{script_location(e, path), "the script failed while loading:\n" + format_traceback(e)};
    }
    impl->watch->disarm();
    if (!globals.contains("fill_angle"))
      return Error{
          path,
          "the script defines no function fill_angle(ctx): define one that returns an angle in degrees"};
    impl->fn = globals["fill_angle"];
    if (!PyCallable_Check(impl->fn.ptr()))
      return Error{path, "fill_angle is not a function (its type is " +
                             py::type::of(impl->fn).attr("__name__").cast<std::string>() +
                             "): define def fill_angle(ctx): ..."};
    impl->globals = std::move(globals);
    impl->namespace_type = py::module_::import("types").attr("SimpleNamespace");
  } catch (py::error_already_set& e) {
    return Error{path, "cannot run the script:\n" + format_traceback(e)};
  }
  return std::unique_ptr<FillAngleScript>(new FillAngleScript(path, std::move(impl)));
}

Result<double> FillAngleScript::angle(const FillAngleContext& c) {
  py::gil_scoped_acquire gil;
  std::string where = where_island(c);
  try {
    py::dict kw;
    kw["layer_index"] = c.layer_index;
    kw["layer_count"] = c.layer_count;
    kw["z"] = c.z;
    kw["z_bottom"] = c.z_bottom;
    kw["layer_height"] = c.z - c.z_bottom;
    kw["island_index"] = c.island_index;
    kw["island_count"] = c.island_count;
    kw["area"] = c.area;
    kw["default_angle"] = c.default_angle;
    py::list holes;
    if (c.shape) {
      BBox2 b = bbox(*c.shape);
      kw["bbox"] = b.empty() ? py::make_tuple(0.0, 0.0, 0.0, 0.0)
                             : py::make_tuple(to_mm(b.min_x), to_mm(b.min_y), to_mm(b.max_x), to_mm(b.max_y));
      kw["outer"] = ring_to_list(c.shape->outer);
      for (const Ring& h : c.shape->holes) holes.append(ring_to_list(h));
    } else {
      kw["bbox"] = py::make_tuple(0.0, 0.0, 0.0, 0.0);
      kw["outer"] = py::list();
    }
    kw["holes"] = holes;
    py::object ctx = impl_->namespace_type(**kw);
    py::object r;
    const double limit = impl_->watch->timeout_s();
    impl_->watch->arm(stuck_message(path_, "fill_angle(ctx) on " + where, limit));
    const auto timed_out = [&] {
      return Error{path_, fmt::format("fill_angle(ctx) took longer than {} on {} (--script-timeout) and was "
                                      "stopped; make the script faster, or raise --script-timeout",
                                      seconds_text(limit), where)};
    };
    try {
      r = impl_->fn(ctx);
    } catch (py::error_already_set& e) {
      if (impl_->watch->disarm()) return timed_out();
      return Error{script_location(e, path_),
                   "fill_angle(ctx) raised an exception on " + where + ":\n" + format_traceback(e)};
    }
    if (impl_->watch->disarm()) return timed_out();
    PyObject* o = r.ptr();
    double v = 0;
    bool number = false;
    if (!PyBool_Check(o)) {
      if (PyFloat_Check(o)) {
        v = PyFloat_AsDouble(o), number = true;
      } else if (PyLong_Check(o)) {
        v = PyLong_AsDouble(o), number = true;
        if (v == -1.0 && PyErr_Occurred()) {
          PyErr_Clear();
          return Error{path_, "fill_angle(ctx) returned an int too large for an angle on " + where};
        }
      } else if (py::isinstance(r, py::module_::import("numbers").attr("Real"))) {
        v = py::float_(r).cast<double>(), number = true;  // numpy.float32 and the like
      }
    }
    if (!number)
      return Error{path_, "fill_angle(ctx) returned " + py::type::of(r).attr("__name__").cast<std::string>() +
                              " " + short_repr(r) + " on " + where +
                              ": it must return a number of degrees (int or float)"};
    if (!std::isfinite(v))
      return Error{path_, "fill_angle(ctx) returned " + short_repr(r) + " on " + where +
                              ": it must return a finite number of degrees"};
    return v;
  } catch (py::error_already_set& e) {
    return Error{path_, "calling fill_angle(ctx) on " + where + " failed:\n" + format_traceback(e)};
  }
}

#else  // no Python in this build

struct FillAngleScript::Impl {};

bool FillAngleScript::available() { return false; }

Result<std::unique_ptr<FillAngleScript>> FillAngleScript::load(const std::string& path, double) {
  if (auto source = read_script(path); !source) return source.error();
  return Error{path,
               "this tranche was built without Python (CMake option TRANCHE_PYTHON=OFF, or pybind11 or the "
               "Python headers were not found): --fill-angle-script is unavailable"};
}

Result<double> FillAngleScript::angle(const FillAngleContext& c) {
  return Error{path_, "no Python in this build (" + where_island(c) + ")"};
}

#endif

FillAngleScript::FillAngleScript(std::string path, std::unique_ptr<Impl> impl)
    : path_(std::move(path)), impl_(std::move(impl)) {}

FillAngleScript::~FillAngleScript() = default;

}  // namespace tranche::geo
