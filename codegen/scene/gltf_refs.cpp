// Scene files' mesh references into glTF files (GltfReferences, gltf.h): each file
// read once per scene, every reference counted against the scene's limit before
// any mesh is allocated, then the meshes read by the import's own code (gltf_read.h).
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "scene/gltf.h"
#include "scene/gltf_read.h"

namespace facet {

namespace fs = std::filesystem;
using gltf_detail::Mat4;
using gltf_detail::MeshSize;
using gltf_detail::PrimitivePlan;
using gltf_detail::Reader;
using gltf_detail::thousands;

namespace {

struct File {
  std::string path;  // as the scene's objects reach it
  tinygltf::Model model;
  std::unique_ptr<Reader> reader;
  bool failed = false;
  size_t last_use = 0;  // the last pending reference that reads it
};

struct Pending {
  size_t object = 0;
  std::string path;  // the object's key path
  File* file = nullptr;
  std::vector<PrimitivePlan> plans;
  Mat4 world;
  MeshSize size;
  long shares = -1;  // the pending reference whose mesh this one shares, or −1
};

// What an object's "mesh" or "node" names: the index of one of `count` items of the
// file's `key` array (`name_of` gives an item's name), else an error for `sink`.
template <class Name>
std::optional<size_t> select(const MeshReference& ref, size_t count, const std::string& key, const File& f,
                             const std::string& path, DiagnosticSink& sink, Name name_of) {
  const std::string at = join_path(path, ref.node ? "node" : "mesh");
  if (ref.index >= 0) {
    if (size_t(ref.index) < count) return size_t(ref.index);
    sink.error(at, fmt::format("{} has no {}[{}]; it has {} ({})", f.path, key, ref.index, count,
                               count ? fmt::format("0 to {}", count - 1) : "none"));
    return std::nullopt;
  }
  std::vector<size_t> hits;
  std::vector<std::string> names;
  for (size_t i = 0; i < count; ++i) {
    names.push_back(name_of(i));
    if (names.back() == ref.name) hits.push_back(i);
  }
  if (hits.size() == 1) return hits[0];
  if (hits.size() > 1) {
    sink.error(at, fmt::format("{} has {} {} named \"{}\" ({}[{}] and {}[{}]); name it by its index", f.path,
                               hits.size(), key, ref.name, key, hits[0], key, hits[1]));
    return std::nullopt;
  }
  std::string hint = suggest(ref.name, names);
  sink.error(at, fmt::format("{} has no {} named \"{}\"{}", f.path, key == "meshes" ? "mesh" : "node", ref.name,
                             hint.empty() ? "" : " (did you mean \"" + hint + "\"?)"));
  return std::nullopt;
}

}  // namespace

struct GltfReferences::Impl {
  std::string scene_file;
  std::map<std::string, std::unique_ptr<File>> files;  // by normalized path
  std::vector<Pending> pending;
  std::map<std::string, size_t> by_key;  // a reference's file, mesh or node and primitive → its pending
  gltf_detail::MeshBudget budget;

  File& open(const std::string& path) {
    std::string key = fs::path(path).lexically_normal().string();
    auto& f = files[key];
    if (f) return *f;
    f = std::make_unique<File>();
    f->path = path;
    std::vector<std::string> notes;  // what import-gltf would note; a scene file is quiet about it
    try {
      f->model = gltf_detail::load_model_file(path, notes);
      f->reader = std::make_unique<Reader>(f->model, path);
    } catch (const InputError&) {
      f->failed = true;
      throw;
    }
    return *f;
  }

  // Which primitives of the file's mesh `mi` the reference takes, planned (morphed and, for a
  // node with a skin, skinned as the import reads them; node_index −1: the mesh alone).
  void plan(Pending& p, const MeshReference& ref, size_t mi, int node_index, const std::string& where,
            DiagnosticSink& sink) {
    const Reader& r = *p.file->reader;
    const auto& mesh = r.model().meshes[mi];
    const std::string mpath = fmt::format("meshes[{}]", mi);
    if (ref.primitive >= 0 && size_t(ref.primitive) >= mesh.primitives.size()) {
      const size_t n = mesh.primitives.size();
      sink.error(join_path(p.path, "primitive"),
                 fmt::format("{}'s {} has {} primitive{} (0 to {})", p.file->path, mpath, n, n == 1 ? "" : "s", n - 1));
      return;
    }
    for (size_t pi = 0; pi < mesh.primitives.size(); ++pi) {
      if (ref.primitive >= 0 ? pi != size_t(ref.primitive) : !gltf_detail::is_triangles(mesh.primitives[pi])) continue;
      p.plans.push_back(gltf_detail::plan_primitive(r, mesh.primitives[pi], fmt::format("{}.primitives[{}]", mpath, pi),
                                                    where, ref.texcoords));
      std::vector<std::string> notes;  // the import said them; a scene file's reference reads the same
      gltf_detail::plan_deformation(r, p.plans.back(), mesh, node_index, notes);
      p.size.vertices += p.plans.back().size.vertices;
      p.size.triangles += p.plans.back().size.triangles;
    }
    if (p.plans.empty())
      sink.error(join_path(p.path, ref.node ? "node" : "mesh"),
                 fmt::format("{}'s {} has no triangle primitives", p.file->path, mpath));
  }

  // The reference's mesh or node, its transform and its primitives; false where it names none.
  bool resolve(Pending& p, const MeshReference& ref, DiagnosticSink& sink, std::string& key) {
    const Reader& r = *p.file->reader;
    const auto& m = r.model();
    if (!ref.node) {
      auto mi = select(ref, m.meshes.size(), "meshes", *p.file, p.path, sink, [&](size_t i) { return m.meshes[i].name; });
      if (!mi) return false;
      key = fmt::format("meshes[{}]", *mi);
      plan(p, ref, *mi, -1, fmt::format("meshes[{}]", *mi), sink);
      return true;
    }
    auto ni = select(ref, m.nodes.size(), "nodes", *p.file, p.path, sink, [&](size_t i) { return m.nodes[i].name; });
    if (!ni) return false;
    const auto& node = m.nodes[*ni];
    if (node.mesh < 0 || size_t(node.mesh) >= m.meshes.size()) {
      sink.error(join_path(p.path, "node"),
                 fmt::format("{}'s nodes[{}]{} has no mesh{}", p.file->path, *ni,
                             node.name.empty() ? "" : " (\"" + node.name + "\")",
                             node.mesh < 0 ? "" : fmt::format(" (its mesh {} is not in \"meshes\")", node.mesh)));
      return false;
    }
    p.world = r.world_matrix(int(*ni));
    key = fmt::format("nodes[{}]", *ni);
    plan(p, ref, size_t(node.mesh), int(*ni), fmt::format("nodes[{}]", *ni), sink);
    return true;
  }

  // A problem inside a glTF file under the object's "gltf" key; one of the scene's as it is.
  void report(const InputError& e, const std::string& path, DiagnosticSink& sink) const {
    for (const auto& d : e.diagnostics()) {
      if (d.file == scene_file) sink.error(d.path, d.message);
      else sink.error(join_path(path, "gltf"), d.format());
    }
  }
};

GltfReferences::GltfReferences(std::string scene_file) : impl_(std::make_unique<Impl>()) {
  impl_->scene_file = std::move(scene_file);
}

GltfReferences::~GltfReferences() = default;

void GltfReferences::add(size_t object, const MeshReference& ref, const std::string& path, DiagnosticSink& sink) {
  Impl& im = *impl_;
  Pending p;
  p.object = object;
  p.path = path;
  try {
    if (!fs::exists(ref.file)) {
      sink.error(join_path(path, "gltf"),
                 fmt::format("no such file: \"{}\" (the path is relative to the scene file)", ref.file));
      return;
    }
    auto it = im.files.find(fs::path(ref.file).lexically_normal().string());
    if (it != im.files.end() && it->second->failed) return;  // reported at its first reference
    p.file = &im.open(ref.file);
    std::string what;  // "nodes[3]"
    if (!im.resolve(p, ref, sink, what) || p.plans.empty()) return;
    if (ref.primitive >= 0) what += fmt::format(" primitive {}", ref.primitive);
    if (ref.texcoords != std::array<int64_t, 2>{0, 1})
      what += fmt::format(" TEXCOORD_{} and _{}", ref.texcoords[0], ref.texcoords[1]);
    std::string key = fs::path(ref.file).lexically_normal().string() + "\n" + what;
    auto seen = im.by_key.find(key);
    if (seen != im.by_key.end()) {
      p.shares = long(seen->second);
    } else {
      im.budget.add(p.size, im.scene_file, path, fmt::format("its mesh, {} of {}", what, ref.file));
      im.by_key[key] = im.pending.size();
    }
    p.file->last_use = im.pending.size();
    im.pending.push_back(std::move(p));
  } catch (const InputError& e) {
    im.report(e, path, sink);
  }
}

void GltfReferences::build(std::vector<Object>& objects, DiagnosticSink& sink) {
  Impl& im = *impl_;
  if (!sink.empty()) return;
  std::map<File*, uint64_t> triangles;
  for (const auto& p : im.pending)
    if (p.shares < 0) triangles[p.file] += p.size.triangles;
  std::map<File*, std::chrono::steady_clock::time_point> started;
  for (size_t i = 0; i < im.pending.size(); ++i) {
    Pending& p = im.pending[i];
    if (triangles[p.file] >= gltf_detail::kProgressTriangles && !started.count(p.file)) {
      started[p.file] = std::chrono::steady_clock::now();
      progress(fmt::format("reading {}: {} triangles", p.file->path, thousands(triangles[p.file])));
    }
    std::shared_ptr<Mesh> mesh;
    try {
      if (p.shares < 0) {
        mesh = std::make_shared<Mesh>();
        mesh->positions.reserve(p.size.vertices);
        mesh->normals.reserve(p.size.vertices);
        mesh->triangles.reserve(p.size.triangles);
        std::vector<std::string> notes;
        for (const auto& plan : p.plans) gltf_detail::append_primitive(*p.file->reader, plan, p.world, *mesh, notes);
        if (mesh->triangles.empty()) p.file->reader->fail(p.plans[0].path, "has no triangles");
      }
    } catch (const InputError& e) {
      im.report(e, p.path, sink);
      return;
    }
    if (p.file->last_use == i) {  // its last reference: the file's buffers go, before the hierarchy is built
      p.file->reader.reset();
      p.file->model = tinygltf::Model();
    }
    if (mesh) mesh->build_bvh();
    objects[p.object].mesh = mesh ? mesh : objects[im.pending[size_t(p.shares)].object].mesh;
    if (p.file->last_use == i && started.count(p.file))
      progress(fmt::format("{}: {} triangles read in {:.1f} s", p.file->path, thousands(triangles[p.file]),
                           std::chrono::duration<double>(std::chrono::steady_clock::now() - started[p.file]).count()));
  }
}

}  // namespace facet
