// Internal to the 3MF loader: what a 3MF package holds besides the model lib3mf reads.
//  - the root model part, from _rels/.rels, so that a ZIP that is no 3MF is named as such;
//  - PrusaSlicer's Metadata/Slic3r_PE_model.config: which triangles of an object are parts, and
//    which are modifiers, negative volumes or support blockers (left out, with a warning);
//  - OrcaSlicer's and Bambu Studio's Metadata/model_settings.config and their objects kept in
//    separate model parts (3D/Objects/*.model, the 3MF production extension), which lib3mf 1.8
//    does not follow: those parts are inlined into the root model and re-packed for lib3mf;
//  - print settings and per-object settings of those slicers: ignored, with a warning.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "base/report.h"
#include "base/result.h"
#include "geometry/plate/threemf_meshes.h"

namespace tranche::plate::threemf {

// A range of an object's triangles that PrusaSlicer keeps as one volume.
struct Volume {
  uint32_t first = 0, last = 0;  // triangle indices, inclusive
  std::string type;              // "ModelPart", "ParameterModifier", "NegativeVolume", "Support..."
  std::string name;
};

struct PrusaObject {
  std::string name;
  std::vector<Volume> volumes;
};

struct Package {
  std::string root;        // the root model part, e.g. "3D/3dmodel.model"
  std::string repacked;    // non-empty: the package lib3mf must read instead of the file's bytes
  // PrusaSlicer's objects, by their position among the model's objects (1, 2, ...: PrusaSlicer
  // numbers its objects in order, as lib3mf numbers the resources it reads).
  std::map<uint32_t, PrusaObject> prusa;
};

// Reads the package's directory and the slicers' extra parts; `file` names it in messages.
// Errors: not a ZIP archive, a ZIP archive that holds no 3D model, broken parts we must read.
Result<Package> inspect_package(std::string_view bytes, const std::string& file, Report& report);

// The package `bytes` with the plain meshes of its model part `root` read into `split` and
// replaced by placeholders (threemf_meshes.h), every part stored uncompressed, for lib3mf; empty
// (and `split` empty) when there is no plain mesh, or the archive cannot be opened here: then
// lib3mf reads `bytes` as it is. An error when a part is damaged (its inflating fails, or its
// CRC-32 or size is not the directory's), which lib3mf would not always see.
Result<std::string> without_meshes(std::string_view bytes, const std::string& root, const std::string& file,
                                   SplitModel& split);

// Why the model part `root` of the package `bytes` is not well-formed XML, or ok. lib3mf 1.8 reads
// a model cut short without complaint; when it finds nothing to print, this says why.
Status check_model_xml(std::string_view bytes, const std::string& root, const std::string& file);

}  // namespace tranche::plate::threemf
