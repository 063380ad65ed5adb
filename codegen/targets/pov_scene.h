// facet — the POV-Ray scene builder, private to codegen/targets: pov.cpp (the
// frame, the plan, the native route) and pov_functions.cpp (function pigments).
#pragma once

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "catalog/program.h"
#include "scene/scene.h"
#include "targets/pov_mesh.h"
#include "targets/pov_printer.h"
#include "targets/pov_texture.h"
#include "targets/targets.h"

namespace facet::targets {

// One material of the scene: its program, the printer with its prefix, and the
// scaffolding functions that shade with it.
struct PovShading {
  const Material* material = nullptr;
  MaterialProgram program;
  PovPrinter printer;
  std::string prefix;      // "" when the scene has one material
  bool dependent = false;  // the reflectance differs per channel: three functions
  ir::FunctionPtr reflect;              // {P}Facet_Reflect(n, l, v): the catalog's inputs from unit vectors
  std::vector<ir::FunctionPtr> lights;  // {P}Facet_Light{i}(x, y, z, n): light i's radiance
  std::vector<ir::FunctionPtr> tables;  // {P}Facet_Table{i}(x, y, z, n·l, n·v), for slope tables (fast route)
  // Where the reflectance differs per channel only through k_d and k_s, objects are shaded
  // lobe by lobe: k_d ⊗ ρ_d + k_s ⊗ ρ_s as a scalar pigment a lobe whose colour map holds its
  // colour: two evaluations a pixel (one for a single lobe) instead of three. Empty: the
  // reflectance whole.
  struct Lobe {
    std::string suffix;                   // "_Diffuse", "_Specular"
    RGB color;                            // k_d or k_s
    ir::FunctionPtr reflect;              // {P}Facet_Reflect{suffix}
    std::vector<ir::FunctionPtr> lights;  // {P}Facet_Light{i}{suffix}
  };
  std::vector<Lobe> lobes;
  // Textured parameters (pov_texture.h): input name → Facet_Sample_<name>(S, T[, R, G, B, A]),
  // the coordinate set it reads, whether it reads an image (S, T) and the vertex colour (R, G,
  // B, A). Non-empty: the scaffolding's functions take S0, T0, S1, T1, and where the material
  // reads the vertex colour R0, G0, B0, A0 too.
  struct Sample {
    ir::FunctionPtr f;
    int uv = 0;
    bool image = true, vertex_color = false;
  };
  std::map<std::string, Sample> samples;
  // {P}Facet_Emission(x, y, z, n, S0, T0, S1, T1[, R0, G0, B0, A0]) = m_a ⊗ A + m_e where m_a or m_e comes from an
  // image (null otherwise: the emission is a colour, emission_texture()).
  ir::FunctionPtr emission_function;
  // A normal map's raw r, g, b at (S, T) of its set (Facet_Sample_normal_map_r, _g, _b), or null.
  std::array<ir::FunctionPtr, 3> normal_map{};
  // The coat's own normal map's (Facet_Sample_coat_normal_map_r, …; Material::coat_normal_map), or null.
  std::array<ir::FunctionPtr, 3> coat_normal_map{};
  int normal_map_uv = 0;  // the set both maps read
  // A map, or lobes whose tangent is the texture frame's (MaterialProgram::uv_tangent), turn on the tangent frame.
  bool framed() const { return normal_map[0] || coat_normal_map[0] || program.uv_tangent(); }
  // A cut-out's alpha from an image (glTF's alphaMode MASK): Facet_Sample_alpha(S, T) of its
  // set, and {P}Facet_Kept(x, y, z, n, …), 1 where alpha ≥ the cutoff, 0 where the surface is
  // cut out, called like a light's function by each object's Facet_Object{o}_Kept. Null where
  // the material has no cut-out or its alpha is a number (PovScene::absent).
  ir::FunctionPtr alpha, kept;
  int alpha_uv = 0;
  bool textured() const { return !samples.empty() || framed() || alpha; }
  int channels() const { return dependent ? 3 : 1; }
  std::string suffix(int ch) const;
  RGB emission(const Scene& s) const;  // m_a ⊗ A + m_e
};

// A pigment holding `radiance(ch)` × weight with transmit t: the function holds
// min(radiance · Π factors(ch), 1) and the colour map scales it back. An empty
// list of factors is a black channel.
struct PovPigment {
  std::function<ir::Expr(int)> radiance;
  std::function<std::vector<ir::Expr>(int)> factors;
  double weight = 1;
  double transmit = 0;
  // Instead of radiance and factors: scalar parts, each a radiance whose colour at 1 is
  // `color` (its pigment is color ⊗ radiance), held as min(radiance · scale · exposure, 1).
  struct Part {
    ir::Expr radiance;
    RGB color;
    double scale;
  };
  std::vector<Part> parts;
};
// `width`: the longest line, counted from the pigment's own indentation.
std::string pov_pigment(const PovPrinter& printer, bool dependent, const PovPigment& p, size_t width);

class PovScene {
 public:
  static constexpr int kTableNodes = 128;  // a slope table's nodes in n·l and in n·v (pov_table.cpp)
  // `stem` starts the names of the files the scene reads (pov_mesh.h).
  PovScene(const Scene& s, const Material* fallback, const std::string& source, PovRoute route = PovRoute::Auto,
           const std::string& stem = "facet");
  std::string render();
  // After render(): the files to write beside the scene, and each object's route.
  std::vector<PovFile>& files() { return files_; }
  const PovPlan& plan() const { return plan_; }
  const std::vector<std::string>& routes() const { return routes_; }
  std::string library();
  std::string sweep();

 private:
  // pov.cpp
  std::string header();
  std::string light_source(const Light& l, std::vector<std::string> extra = {}, double scale = 1,
                           const std::string& comment = "");
  std::string object(size_t o, double shrink, const std::string& body, const std::string& modifiers);
  std::string mesh(size_t o, double shrink, const std::string& body, const std::string& modifiers);
  std::string native_light(size_t i);
  std::string native();
  // pov_functions.cpp
  void build_scaffolding();
  std::string texture_declarations() const;
  ir::FunctionPtr reflect_function(PovShading& sh, const ir::FunctionPtr& reflectance, const std::string& suffix);
  ir::FunctionPtr light_function(PovShading& sh, size_t i, const ir::FunctionPtr& reflect, const std::string& suffix);
  ir::FunctionPtr emission_function(PovShading& sh);
  ir::FunctionPtr kept_function(PovShading& sh);
  // `name`(x, y, z): `light` (a function of the point, its normal and its texture coordinates) on object o;
  // `light_index`: the scene light it is, where there is one (not the emission's function).
  // `own_normal`: `light` takes the coat's normal (the surface's own, or the coat's own normal
  // map's), not the normal map's, and no tangent (the emission's function, whose weight reads it).
  ir::FunctionPtr object_function(size_t o, const std::string& name, const ir::FunctionPtr& light,
                                  std::optional<size_t> light_index = std::nullopt, bool own_normal = false);
  // Constants, terms and frames; `objects`: those the scene's objects call (lobe by lobe
  // where PovShading::lobes), else the whole reflectance's (the library, the sweep).
  std::string functions(bool objects = false);
  std::vector<ir::FunctionPtr> reflect_roots(const PovShading& sh, bool objects) const;
  std::string lights();
  std::string mesh_declarations(size_t o);
  void register_mesh_files();
  std::string lit(size_t o, size_t i, double weight, double t, double shrink, const std::string& mods);
  std::string emitting(size_t o, double weight, double t, double shrink, const std::string& mods);
  // `pigment` (a pigment { … } of object o) cut out where its material's alpha is below its
  // cutoff: clear there (rgbt 1), which camera and shadow rays pass. Unchanged without a cut-out.
  std::string cut(size_t o, const std::string& pigment) const;
  // Whether object o is not there at all: its material's alpha is a number below its cutoff.
  bool absent(size_t o) const;
  std::string pass(size_t item);
  std::string passes();
  std::string point_shade();
  // pov_table.cpp
  ir::FunctionPtr table_function(PovShading& sh, size_t i);
  std::string table_pigment(size_t o, size_t i, PovPigment p, size_t width);

  const PovShading& shading(size_t o) const { return *shadings_[shading_of_[o]]; }

  const Scene& s_;
  std::string source_;
  PovPlan plan_;
  std::vector<std::unique_ptr<PovShading>> shadings_;
  std::vector<size_t> shading_of_;
  // [o][i]: Facet_Object{o}_Light{i}, or one function per lobe (PovShading::lobes).
  std::vector<std::vector<std::vector<ir::FunctionPtr>>> objects_;
  std::vector<ir::FunctionPtr> emissions_;  // [o]: Facet_Object{o}_Emission where its emission is textured
  std::vector<ir::FunctionPtr> kept_;       // [o]: Facet_Object{o}_Kept where its material cuts it out by an image
  std::string stem_;
  std::vector<PovMeshData> data_;      // [o]: a mesh's data image on the function route
  std::vector<PovTexture> textures_;   // the images textured parameters read
  void register_textures();
  std::vector<bool> table_;            // [o]: a mesh drawn through slope tables (fast route)
  std::set<std::string> declared_tables_;
  std::vector<PovFile> files_;
  std::vector<std::string> routes_;    // [o]: how object o is drawn
  double scale_ = 1;
  size_t indent_ = 0;  // of the objects being printed: 2 inside a light_group
};

// Helpers of both files.
bool pov_grey(const RGB& c);
bool pov_black(const RGB& c);
std::string emission_texture(const RGB& e, double weight, double t);
// Whether object i is drawn through slope tables: a mesh with an isotropic
// material, on the function route, when the route asked is fast.
bool pov_table_object(const Scene& s, size_t i, const Material* fallback, PovRoute route, bool native);
// A slope table's error relative to max(1, |reflectance|), measured at its cells' centres
// (pov_table.cpp): the largest, and the share of cells where it is over 2e-3.
struct TableError {
  double worst = 0, share_over = 0;
};
TableError table_error(const Material& m);
// `texture { … }` of a native finish, from the catalog's PovFinish of each lobe.
std::string native_texture(const Material& m, double weight);

}  // namespace facet::targets
