// plate_bench: the plate's loaders and arrangement (bench_plate.sh prints the table).
//   plate_bench load DIR [RUNS]        10 objects, 2 000 000 triangles: the same meshes as 10
//                                      STL files and as one 3MF; load time of each repeated in
//                                      this process (best of RUNS, default 3), their ratio, the
//                                      CPU time of each (all threads: what a load costs when
//                                      others share the machine), the time only inflating the
//                                      3MF's model part takes (the floor: deflate is inflated by
//                                      one thread), the scanner reading its meshes from the
//                                      inflated text alone, and lib3mf reading the whole package alone
//                                      (what the loader used to do). The goal is judged on loads
//                                      in fresh processes (bench_plate.sh, with `read`)
//   plate_bench read RUNS FILE...      loads the FILEs (3MF, STL, OBJ) RUNS times; prints the best
//                                      wall and CPU time, s, and the peak memory, MiB (RUNS 1: a
//                                      first load, in a fresh process; more: a loop to profile
//                                      with perf record)
//   plate_bench write-objects DIR      the arrangement's 50 objects as DIR/obj00.stl ... obj49.stl
//   plate_bench arrange DIR [PEER.3mf] arranges them on a 250 × 210 mm bed, 6 mm apart: time
//                                      (best of 3) and packing density (hull areas over the pile's
//                                      bounding box), and the same density of PEER.3mf (the same
//                                      objects as PrusaSlicer arranged them)
#include <Model/COM/NMR_DLLInterfaces.h>

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "geometry/mesh/file_bytes.h"
#include "geometry/mesh/primitives.h"
#include "geometry/mesh/stl.h"
#include "geometry/plate/model_file.h"
#include "geometry/plate/plate.h"
#include "geometry/plate/threemf_meshes.h"
#include "geometry/plate/threemf_write.h"
#include "geometry/plate/transform.h"
#include "geometry/plate/zip.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

int fail(const std::string& msg) {
  std::fprintf(stderr, "plate_bench: %s\n", msg.c_str());
  return 1;
}

// The process's CPU time (all threads, user and system), s.
double cpu_now() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// The best wall time of `runs` calls of f; `cpu`, if given: the least CPU time of a call. On a
// machine others share, the CPU time says what a load costs when the wall time is inflated by
// waiting for a core.
template <class F>
double best_of(int runs, F f, double* cpu = nullptr) {
  double best = 1e300, best_cpu = 1e300;
  for (int i = 0; i < runs; ++i) {
    const auto t = Clock::now();
    const double c = cpu_now();
    if (!f()) return -1;
    best = std::min(best, since(t));
    best_cpu = std::min(best_cpu, cpu_now() - c);
  }
  if (cpu) *cpu = best_cpu;
  return best;
}

// Ten tori of 200 000 triangles each, of different sizes, side by side.
// Loads every file of `files` onto one plate, all objects kept until the last is loaded (as a
// plate keeps them); the number of objects, or -1 after saying why a file did not load.
long load_plate(const std::vector<std::string>& files, Report& report) {
  std::vector<plate::Object> plate;
  for (const auto& file : files) {
    auto o = plate::load_model_file(file, report);
    if (!o) {
      fmt::print(stderr, "plate_bench: {}\n", o.error().to_string());
      return -1;
    }
    for (auto& x : *o) plate.push_back(std::move(x));
  }
  return static_cast<long>(plate.size());
}

std::vector<plate::Object> load_set() {
  std::vector<plate::Object> out;
  for (int i = 0; i < 10; ++i) {
    plate::Object o;
    o.name = fmt::format("torus{}", i);
    o.mesh = geo::torus(15 + i, 4 + 0.3 * i, 500, 200);
    o.transform = Eigen::Translation3d(30 + 62 * (i % 5), 30 + 62 * (i / 5), 4 + 0.3 * i);  // apart
    out.push_back(std::move(o));
  }
  return out;
}

int load(const std::string& dir, int runs) {
  fs::create_directories(dir);
  const auto set = load_set();
  std::vector<std::string> stls;
  size_t triangles = 0, stl_bytes = 0;
  for (const auto& o : set) {
    stls.push_back(fmt::format("{}/{}.stl", dir, o.name));
    if (auto s = geo::write_stl_binary(stls.back(), plate::world_mesh(o)); !s) return fail(s.error().to_string());
    triangles += o.mesh.triangles.size();
    stl_bytes += fs::file_size(stls.back());
  }
  const std::string three = dir + "/ten.3mf";
  if (auto s = plate::write_3mf(three, set); !s) return fail(s.error().to_string());
  Report report;
  double stl_cpu = 0, three_cpu = 0, inflate_cpu = 0;
  const double stl_s = best_of(
      runs,
      [&] { return load_plate(stls, report) == static_cast<long>(stls.size()); },
      &stl_cpu);
  size_t loaded = 0;
  const double three_s = best_of(
      runs,
      [&] {
        auto objects = plate::load_model_file(three, report);
        loaded = objects ? objects->size() : 0;
        return objects.ok();
      },
      &three_cpu);
  if (stl_s < 0 || three_s < 0 || loaded != 10) return fail("a load failed");
  auto bytes = geo::read_file_bytes(three);
  if (!bytes) return fail(bytes.error().to_string());
  size_t model_bytes = 0;
  const double inflate_s = best_of(
      runs,
      [&] {
        auto zip = plate::ZipArchive::open(bytes->view(), three);
        if (!zip) return false;
        auto in = zip->stream(*zip->find("3D/3dmodel.model"));  // as the loader reads it: 1 MiB at a time
        if (!in) return false;
        std::vector<char> window(size_t{1} << 20);
        model_bytes = 0;
        for (;;) {
          auto got = in->read(window.data(), window.size());
          if (!got) return false;
          if (*got == 0) return true;
          model_bytes += *got;
        }
      },
      &inflate_cpu);
  // The scanner alone reading the meshes of the model part, inflated beforehand into chunks as the
  // inflating thread hands them over (plate/threemf_meshes.h), welder's order included.
  struct Inflated : plate::threemf::Chunks {
    std::vector<std::unique_ptr<char[]>> memory;
    std::vector<Chunk> all;
    size_t next_chunk = 0;
    std::optional<Chunk> next() override { return next_chunk < all.size() ? all[next_chunk++] : Chunk{}; }
    void give_back(char*) override {}
  } inflated;
  {
    auto zip = plate::ZipArchive::open(bytes->view(), three);
    if (!zip) return fail(zip.error().to_string());
    auto in = zip->stream(*zip->find("3D/3dmodel.model"));
    if (!in) return fail(in.error().to_string());
    for (;;) {
      constexpr size_t kChunk = size_t{1} << 20;
      auto& m =
          inflated.memory.emplace_back(std::make_unique_for_overwrite<char[]>(Inflated::kRoom + kChunk));
      size_t got = 0;
      while (got < kChunk) {
        auto n = in->read(m.get() + Inflated::kRoom + got, kChunk - got);
        if (!n) return fail(n.error().to_string());
        if (*n == 0) break;
        got += *n;
      }
      if (got == 0) break;
      inflated.all.push_back({m.get(), got});
    }
  }
  double scan_cpu = 0;
  const double scan_s = best_of(
      runs,
      [&] {
        inflated.next_chunk = 0;
        auto split = plate::threemf::split_meshes_streamed(inflated);
        return split && split->meshes.size() == 10;
      },
      &scan_cpu);
  // lib3mf alone reading the package into its model (inflating included), before we read a vertex.
  const double lib3mf_s = best_of(runs, [&] {
    NMR::PLib3MFModel* model = nullptr;
    NMR::PLib3MFModelReader* reader = nullptr;
    bool ok = NMR::lib3mf_createmodel(&model) == LIB3MF_OK &&
              NMR::lib3mf_model_queryreader(model, "3mf", &reader) == LIB3MF_OK &&
              NMR::lib3mf_reader_readfrombuffer(reader, reinterpret_cast<BYTE*>(const_cast<char*>(bytes->view().data())),
                                                bytes->view().size()) == LIB3MF_OK;
    if (reader) NMR::lib3mf_release(reader);
    if (model) NMR::lib3mf_release(model);
    return ok;
  });
  fmt::print("loads repeated in one process (best of {}; memory the previous load freed is reused, which spares the STL\n"
             "files' 100 MB most of their page faults: not what `tranche slice` sees, see the fresh-process table)\n",
             runs);
  fmt::print("{:<34} {:>10} {:>9} {:>9} {:>8} {:>7} {:>8}\n", "input (10 objects)", "triangles", "file MB", "load s",
             "vs STL", "CPU s", "vs STL");
  fmt::print("{:<34} {:>10} {:>9.1f} {:>9.3f} {:>8} {:>7.3f} {:>8}\n", "10 binary STL files", triangles, stl_bytes / 1e6,
             stl_s, "1.00", stl_cpu, "1.00");
  fmt::print("{:<34} {:>10} {:>9.1f} {:>9.3f} {:>8.2f} {:>7.3f} {:>8.2f}\n", "one 3MF (mesh scanner + lib3mf)",
             triangles, fs::file_size(three) / 1e6, three_s, three_s / stl_s, three_cpu, three_cpu / stl_cpu);
  fmt::print("{:<34} {:>10} {:>9.1f} {:>9.3f} {:>8.2f} {:>7.3f} {:>8.2f}   (ISA-L, one thread, 1 MiB at a time: the "
             "floor of the CPU time)\n",
             "  inflating its model part only", "", model_bytes / 1e6, inflate_s, inflate_s / stl_s, inflate_cpu,
             inflate_cpu / stl_cpu);
  fmt::print(
      "{:<34} {:>10} {:>9.1f} {:>9.3f} {:>8.2f} {:>7.3f} {:>8.2f}   (inflated beforehand; {:.1f} GB/s of "
      "XML)\n",
      "  reading its meshes only", "", model_bytes / 1e6, scan_s, scan_s / stl_s, scan_cpu,
      scan_cpu / stl_cpu, model_bytes / scan_cpu / 1e9);
  fmt::print("{:<34} {:>10} {:>9} {:>9.3f} {:>8.2f}   (lib3mf's XML reader, inflating included)\n",
             "  lib3mf reading the package only", "", "", lib3mf_s, lib3mf_s / stl_s);
  return 0;
}

// Loads `files` (each a 3MF, STL, OBJ) `runs` times; prints the best wall and CPU time of loading
// them all, in seconds, and the process's peak memory (resident, MiB).
int read(int runs, const std::vector<std::string>& files) {
  Report report;
  double cpu = 0;
  const double s = best_of(
      runs,
      [&] { return load_plate(files, report) >= 0; },
      &cpu);
  if (s < 0) return 1;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  fmt::print("{:.4f} {:.4f} {:.1f}\n", s, cpu, static_cast<double>(u.ru_maxrss) / 1024);  // ru_maxrss: KiB
  return 0;
}

// 50 objects of 8 kinds and random sizes (a fixed seed), some turned: what a plate of parts is.
std::vector<geo::Mesh> arrange_set() {
  std::mt19937 rng(50);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<geo::Mesh> out;
  for (int i = 0; i < 50; ++i) {
    const double a = 10 + 22 * u(rng), b = 8 + 20 * u(rng), h = 3 + 10 * u(rng);
    geo::Mesh m;
    switch (i % 8) {
      case 0: m = geo::box({a, b, h}); break;
      case 1: m = geo::cylinder(a / 2, h, 48); break;
      case 2: m = geo::cone(a / 2, a / 6, h, 48); break;
      case 3: m = geo::torus(a / 2, std::min(a, b) / 8, 64, 16); break;
      case 4:  // an L
        m = geo::box({a, b / 3, h});
        geo::append(m, geo::box({b / 3, b, h}, {0, b / 3, 0}));
        break;
      case 5: m = geo::plate_with_holes(a, b, 3, 2, 2, std::min(a, b) / 8, 16); break;
      case 6: m = geo::sphere(std::min(a, b) / 2, 32, 16); break;
      default: m = geo::box({a * 1.5, b / 2, h}); break;
    }
    if (i % 3 == 1) {  // turned at an angle, so that hulls are not all square to the bed
      plate::Object o;
      o.mesh = m;
      o.transform = Eigen::AngleAxisd(u(rng) * M_PI, Eigen::Vector3d::UnitZ());
      m = plate::world_mesh(o);
    }
    out.push_back(std::move(m));
  }
  return out;
}

int write_objects(const std::string& dir) {
  fs::create_directories(dir);
  const auto set = arrange_set();
  for (size_t i = 0; i < set.size(); ++i)
    if (auto s = geo::write_stl_binary(fmt::format("{}/obj{:02}.stl", dir, i), set[i]); !s)
      return fail(s.error().to_string());
  std::printf("wrote %zu objects to %s\n", set.size(), dir.c_str());
  return 0;
}

// Hull areas over the area of the pile's bounding box.
double density(const plate::Plate& p, double* w = nullptr, double* h = nullptr) {
  double hulls = 0;
  plate::Box2 pile;
  for (const auto& o : p.objects) {
    const plate::Convex c = plate::footprint(o);
    hulls += plate::area(c);
    pile.add(plate::bounds(c));
  }
  if (w) *w = pile.size().x();
  if (h) *h = pile.size().y();
  return hulls / (pile.size().x() * pile.size().y());
}

int arrange(const std::string& dir, const std::string& peer) {
  plate::PlateOptions opt;
  for (int i = 0; i < 50; ++i) opt.files.push_back(fmt::format("{}/obj{:02}.stl", dir, i));
  plate::Bed bed;
  bed.size_x_mm = 250;
  bed.size_y_mm = 210;
  Report report;
  auto loaded = plate::load_plate(opt.files, report);
  if (!loaded) return fail(loaded.error().to_string());
  if (auto s = plate::apply_transforms(*loaded, opt, bed, report); !s) return fail(s.error().to_string());
  plate::Plate arranged;
  const double t = best_of(3, [&] {
    arranged = *loaded;
    return plate::place_objects(arranged, opt, bed).ok();
  });
  if (t < 0) return fail("the arrangement failed");
  if (auto s = plate::check_plate(arranged, bed, false, report); !s) return fail(s.error().to_string());
  double w = 0, h = 0;
  const double ours = density(arranged, &w, &h);
  fmt::print("{:<34} {:>8} {:>9} {:>14} {:>8}\n", "arrangement of 50 objects", "time s", "density", "pile mm",
             "vs peer");
  fmt::print("{:<34} {:>8.3f} {:>9.3f} {:>14} {:>8}   limit 1 s: {}\n", "tranche (convex hulls, 6 mm)", t, ours,
             fmt::format("{:.0f} × {:.0f}", w, h), "", t < 1 ? "met" : "MISSED");
  if (peer.empty()) return 0;
  auto objects = plate::load_model_file(peer, report);
  if (!objects) return fail(objects.error().to_string());
  plate::Plate theirs;
  theirs.objects = std::move(*objects);
  if (theirs.objects.size() != 50) return fail(fmt::format("{} has {} objects, not 50", peer, theirs.objects.size()));
  Report peer_report;
  (void)plate::check_plate(theirs, plate::Bed{.size_x_mm = 1e4, .size_y_mm = 1e4, .origin_x_mm = -5e3, .origin_y_mm = -5e3},
                           true, peer_report);
  if (peer_report.count("plate-overlap") > 0) return fail(fmt::format("{}: objects overlap", peer));
  const double prusa = density(theirs, &w, &h);
  fmt::print("{:<34} {:>8} {:>9.3f} {:>14} {:>8.2f}   goal within 10%: {}\n", "PrusaSlicer --arrange (6 mm)", "",
             prusa, fmt::format("{:.0f} × {:.0f}", w, h), ours / prusa, ours >= 0.9 * prusa ? "met" : "MISSED");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  if (cmd == "load" && argc >= 3) return load(argv[2], argc > 3 ? std::atoi(argv[3]) : 3);
  if (cmd == "read" && argc >= 4) return read(std::atoi(argv[2]), std::vector<std::string>(argv + 3, argv + argc));
  if (cmd == "write-objects" && argc == 3) return write_objects(argv[2]);
  if (cmd == "arrange" && argc >= 3) return arrange(argv[2], argc > 3 ? argv[3] : "");
  std::fprintf(stderr, "usage: plate_bench load DIR [RUNS] | write-objects DIR | arrange DIR [PEER.3mf]\n");
  return 2;
}
