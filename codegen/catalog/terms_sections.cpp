// The building blocks of the catalog that are not lobes on their own: Fresnel
// and geometry terms, distributions, modifiers, ambient and emission, lights
// and attenuation laws. They carry documentation and the parameters material
// and scene files give them; their formulas are the term functions.
#include "catalog/catalog_internal.h"

namespace facet::catalog_detail {

namespace {
// η in [1e-3, 1e4] (docs/float32.md): at normal incidence the exact Fresnel term's
// c(g + c) − 1 and c(g − c) + 1 both cancel to about η, which float32 computes from
// numbers near 1 to one ulp (1.2e-7): η ≥ 1e-3 keeps their ratio to 1e-4; below
// 1.1e-19, η² flushes to 0 and the ratio is 0/0.
const Range kIorRange = {1e-3, kScalarMax, false, false, true};

ModelDef entry(std::string section, std::string name, std::string title, std::string citation,
               std::string formula, std::string doc) {
  ModelDef m;
  m.section = std::move(section);
  m.name = std::move(name);
  m.title = std::move(title);
  m.citation = std::move(citation);
  m.formula = std::move(formula);
  m.doc = std::move(doc);
  return m;
}

// Layering operators: how a material combines lobes, each weighted by what another does
// not reflect (glTF 2.0 Appendix B, "Material Structure"). Their functions are in terms::.
void add_layering_operators(std::vector<ModelDef>& all) {
  all.push_back(entry("layering", "fresnel_mix", "Fresnel mix",
                      "glTF 2.0 Appendix B, \"Fresnel\"; KHR_materials_specular, \"Implementation\"",
                      "fresnel_mix(F, base, layer) = F ⊗ layer + (1 − max(F)) base, "
                      "F = f0 + (f90 − f0)(1 − |v·h|)^5",
                      "A specular layer over a diffuse base: the base gets the light the layer's Fresnel term "
                      "does not reflect. With a grey f0 and f90 = 1 it is Appendix B's mix(base, layer, F)."));
  all.push_back(entry("layering", "conductor_fresnel", "Conductor Fresnel", "glTF 2.0 Appendix B, \"Fresnel\"",
                      "conductor_fresnel(f0, bsdf) = bsdf ⊗ (f0 + (1 − f0)(1 − |v·h|)^5)",
                      "A metal: the specular lobe tinted by Schlick's Fresnel term of the base colour."));
  all.push_back(entry("layering", "mix", "Mix", "glTF 2.0 Appendix B, \"General\"",
                      "mix(a, b, t) = (1 − t) a + t b",
                      "Two materials blended by a weight: glTF's dielectric and metal by `metallic`."));
}
}  // namespace

void add_terms(std::vector<ModelDef>& all) {
  // Fresnel
  all.push_back(entry("fresnel", "none", "No Fresnel", "", "F = 1", "Reflection independent of angle."));
  {
    auto m = entry("fresnel", "schlick", "Schlick's Fresnel",
                   "Schlick 1994, \"An Inexpensive BRDF Model for Physically-based Rendering\"",
                   "F = f0 + (1 − f0)(1 − v·h)^5",
                   "Reflectance at normal incidence f0 (RGB for metals), rising to 1 at grazing angles.");
    m.params = {color("f0", "reflectance at normal incidence", Range::closed(0, 1), {0.04, 0.04, 0.04}, true)};
    m.normal_reflectance = [](const ModelSpec& f) { return f.at("f0").rgb; };
    all.push_back(m);
  }
  {
    auto m = entry("fresnel", "exact", "Exact dielectric Fresnel",
                   "Cook & Torrance 1982, after Fresnel", "g = √(η² + c² − 1), F = ½ (g−c)²/(g+c)² (1 + ((c(g+c)−1)/(c(g−c)+1))²), c = v·h",
                   "Unpolarized reflectance of a dielectric of relative index η; F = 1 under total internal "
                   "reflection (η² + c² − 1 < 0).");
    m.params = {number("ior", "relative index of refraction η", kIorRange, 1.5)};
    all.push_back(m);
  }
  // Geometry
  all.push_back(entry("geometry", "none", "No masking", "", "G = 1", "Facets neither mask nor shadow each other."));
  all.push_back(entry("geometry", "v_cavity", "V-cavity masking", "Cook & Torrance 1982",
                      "G = min(1, 2(n·h)(n·v)/(v·h), 2(n·h)(n·l)/(v·h))",
                      "Symmetric V-grooves: the fraction of a facet that is both lit and seen."));
  all.push_back(entry("geometry", "smith_ggx", "Smith GGX, separable", "Walter et al. 2007, after Smith 1967",
                      "G = G1(n·l) G1(n·v), G1(x) = 2x/(x + √(α² + (1−α²)x²))",
                      "Uncorrelated masking and shadowing for the GGX distribution; α is the lobe's roughness."));
  all.push_back(entry("geometry", "smith_ggx_correlated", "Smith GGX, height-correlated",
                      "Heitz 2014, \"Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs\"; "
                      "glTF 2.0 Appendix B, \"Specular BRDF\"",
                      "V = G/(4 (n·l)(n·v)) = 1/(2((n·v)√(α² + (1−α²)(n·l)²) + (n·l)√(α² + (1−α²)(n·v)²)))",
                      "Masking and shadowing correlated by the height of the facet: the form glTF's BRDF uses. "
                      "Never darker than the separable form, which counts a facet high enough to be seen "
                      "and lit twice."));
  // Distributions
  all.push_back(entry("distribution", "beckmann", "Beckmann distribution", "Beckmann & Spizzichino 1963",
                      "D = exp(−tan²θ_h/m²)/(π m² cos⁴θ_h)", "Gaussian facet slopes of RMS m."));
  all.push_back(entry("distribution", "ggx", "GGX / Trowbridge–Reitz distribution",
                      "Walter et al. 2007; Trowbridge & Reitz 1975", "D = α²/(π((n·h)²(α²−1)+1)²)",
                      "Ellipsoidal facets; a longer tail than Beckmann."));
  all.push_back(entry("distribution", "trowbridge_reitz", "Trowbridge–Reitz, Blinn's form",
                      "Blinn 1977", "D = (c²/((n·h)²(c²−1)+1))²", "Unnormalized; c is the eccentricity."));
  add_layering_operators(all);
  // Modifiers
  {
    auto m = entry("modifier", "toon", "Toon", "Lake et al. 2000, \"Stylized Rendering Techniques for Scalable Real-Time 3D Animation\"",
                   "ρ' = smoothstep(cutoff − width/2, cutoff + width/2, ρ); width 0: ρ' = [ρ ≥ cutoff]",
                   "Quantizes a lobe into flat bands, as in cartoons. Any diffuse or specular lobe takes it.");
    m.params = {number("cutoff", "the value of ρ where the band changes", Range::scalar(), 0.5),
                number("width", "width of the smooth transition; 0 is a hard step", Range::scalar(), 0, false)};
    m.cycles = approximate("diffuse_toon / glossy_toon step on angles, not on ρ");
    m.pov = none("function pigment");
    m.blender_nodes = nodes_approximate(
        "Toon BSDF, Size and Smooth from the angles where ρ = cutoff ± width/2, colour k·2(1 − cos θ): exact for "
        "lambert and phong with width 0 (Diffuse and Glossy Toon step on exactly their angles); linear in the angle "
        "where facet's smoothstep is in ρ with a width (the figure: toon.json's lambert, width 0.1); no Toon BSDF "
        "steps on the other lobes' angles (blinn_phong's angle(n, h) taken as half the mirrored one is 0.80 off)",
        0.0969);
    all.push_back(m);
  }
  all.push_back(entry("modifier", "schlick_approximation", "Schlick's power approximation",
                      "Schlick 1994, \"An Inexpensive BRDF Model for Physically-based Rendering\"",
                      "x^n ≈ x / (n − n x + x)",
                      "Replaces the power of phong and blinn_phong (\"approximation\": \"schlick\")."));
  // Ambient and emission
  all.push_back(entry("term", "ambient", "Ambient", "", "m_a ⊗ A",
                      "The material's ambient colour times the scene's ambient colour A, added unlit. m_a may come "
                      "from an image (\"ambient\": {\"texture\": …}; docs/textures.md), clamped at 0."));
  all.push_back(entry("term", "emission", "Emission", "", "m_e",
                      "Radiance the surface emits by itself, added unlit. m_e may come from an image "
                      "(\"emission\": {\"texture\": …}; docs/textures.md), clamped at 0."));
}

namespace {
ParamDef attenuation_param() {
  ParamDef p = model("attenuation", "distance attenuation att(d)", "attenuation", "none");
  p.fixed = "polynomial";  // {"constant": …, "linear": …, "quadratic": …}
  return p;
}
}  // namespace

void add_lights(std::vector<ModelDef>& all) {
  {
    auto m = entry("light", "point", "Point light", "", "l = normalize(p_light − p), d = |p_light − p|",
                   "Light from a point, attenuated by the light's attenuation law.");
    m.params = {vector("position", "world position", {0, 0, 0}, true),
                color("color", "colour C", Range::light_color(), {1, 1, 1}), attenuation_param()};
    m.light_type = LightType::Point;
    all.push_back(m);
  }
  {
    auto m = entry("light", "directional", "Directional light", "", "l = −normalize(direction)",
                   "Light from infinitely far away; never attenuated.");
    m.params = {vector("direction", "the way the light travels", {0, -1, 0}, true, true),
                color("color", "colour C", Range::light_color(), {1, 1, 1})};
    m.light_type = LightType::Directional;
    all.push_back(m);
  }
  {
    auto m = entry("light", "spot", "Spot light", "OpenGL 1.0 fixed-function spotlight",
                   "spot = [−l·s]^exponent inside the cutoff cone, 0 outside",
                   "A point light restricted to a cone around its direction s.");
    m.params = {vector("position", "world position", {0, 0, 0}, true),
                vector("direction", "the axis of the cone", {0, -1, 0}, true, true),
                number("cutoff", "half-angle of the cone in degrees", Range::open(0, 90), 30),
                number("exponent", "concentration towards the axis", Range::exponent(0), 0, false),
                color("color", "colour C", Range::light_color(), {1, 1, 1}), attenuation_param()};
    m.pov = exact("spotlight with radius = falloff = cutoff and tightness = exponent");
    m.light_type = LightType::Spot;
    all.push_back(m);
  }
  {
    auto m = entry("attenuation", "none", "No attenuation", "", "att(d) = 1", "The default.");
    m.attenuation_law = AttenuationLaw::None;
    all.push_back(m);
  }
  {
    auto m = entry("attenuation", "inverse_square", "Inverse square", "", "att(d) = 1/d²",
                   "The physical falloff of a point source.");
    m.pov = exact("fade_distance 0 fade_power 2 (POV-Ray then multiplies by d^−2)");
    m.attenuation_law = AttenuationLaw::InverseSquare;
    all.push_back(m);
  }
  {
    auto m = entry("attenuation", "polynomial", "Polynomial attenuation",
                   "Foley, van Dam, Feiner & Hughes 1990, \"Computer Graphics: Principles and Practice\", eq. 16.8",
                   "att(d) = min(1, 1/(c1 + c2 d + c3 d²))",
                   "Written {\"constant\": c1, \"linear\": c2, \"quadratic\": c3}. OpenGL's and Direct3D's "
                   "fixed-function law is the same polynomial without the min(1, ·); the two agree when c1 ≥ 1.");
    m.params = {number("constant", "c1", Range::scalar(), 1, false),
                number("linear", "c2", Range::scalar(), 0, false),
                number("quadratic", "c3", Range::scalar(), 0, false)};
    m.pov = approximate("exact through fade when c1 ≥ 1 and one of c2, c3 is 0; otherwise in the pigment");
    m.attenuation_law = AttenuationLaw::Polynomial;
    all.push_back(m);
  }
  {
    auto m = entry("attenuation", "inverse_square_range", "Inverse square within a range",
                   "KHR_lights_punctual (Khronos 2018), \"Range Property\"", "att(d) = clamp(1 − (d/r)⁴, 0, 1) / d²",
                   "Written {\"model\": \"inverse_square_range\", \"range\": r}: the physical falloff, windowed "
                   "smoothly to 0 at the light's range r, as glTF's KHR_lights_punctual recommends for its `range`.");
    m.params = {number("range", "the distance r at which the light reaches 0", Range::positive_coordinate(), 10)};
    m.pov = approximate("in the pigment (no POV-Ray fade has the window)");
    m.attenuation_law = AttenuationLaw::InverseSquareRange;
    all.push_back(m);
  }
}

namespace {
void add_cameras(std::vector<ModelDef>& all) {
  {
    auto m = entry("camera", "perspective", "Perspective camera", "",
                   "ray(i, j) through pixel centres; fov is the vertical field of view",
                   "A pinhole camera at `position` looking at `look_at`, rolled so `up` points up.");
    m.params = {vector("position", "where the camera is", {0, 0, 4}, true),
                vector("look_at", "the point at the image centre", {0, 0, 0}),
                vector("up", "the world direction that is up in the image", {0, 1, 0}, false, true),
                number("fov", "vertical field of view in degrees", Range::open(0, 180), 40, false)};
    all.push_back(m);
  }
  {
    auto m = entry("camera", "orthographic", "Orthographic camera", "",
                   "ray(i, j): origin on the image plane through pixel centres, direction the view's; height is the "
                   "view's vertical extent",
                   "Parallel rays along look_at − position from a rectangle `height` high (the image's aspect gives "
                   "its width) centred at `position`, rolled so `up` points up; written with \"type\": "
                   "\"orthographic\". glTF's orthographic camera has height = 2·ymag.");
    m.params = {vector("position", "the centre of the image rectangle", {0, 0, 4}, true),
                vector("look_at", "a point the view direction passes through from position", {0, 0, 0}),
                vector("up", "the world direction that is up in the image", {0, 1, 0}, false, true),
                number("height", "the vertical extent of the view, world units", Range::positive_coordinate(), 2,
                       false)};
    all.push_back(m);
  }
}
}  // namespace

void add_scene_vocabulary(std::vector<ModelDef>& all) {
  add_cameras(all);
  {
    auto m = entry("object", "sphere", "Sphere", "", "|p − center| = radius", "An analytic sphere.");
    m.params = {text("name", "a name for reports"), text("material", "a key of the scene's \"materials\""),
                vector("center", "centre", {0, 0, 0}, true), number("radius", "radius", Range::positive_coordinate(), 1)};
    m.object_type = ObjectType::Sphere;
    all.push_back(m);
  }
  {
    auto m = entry("object", "plane", "Plane (square)", "", "(p − point)·normal = 0, |in-plane offset| ≤ size",
                   "A square of half-side `size` centred at `point`, facing `normal`. Its edges run along "
                   "normalize(normal × x̂) and normal × that (× ẑ when normal is along x̂).");
    m.params = {text("name", "a name for reports"), text("material", "a key of the scene's \"materials\""),
                vector("point", "centre of the square", {0, 0, 0}, true),
                vector("normal", "the side the square faces", {0, 1, 0}, true, true),
                number("size", "half the side of the square", Range::positive_coordinate(), 10, false)};
    m.object_type = ObjectType::Plane;
    all.push_back(m);
  }
  {
    auto m = entry("object", "mesh", "Triangle mesh", "", "n(p) = normalize(Σ w_i n_i), w the barycentrics of p",
                   "Triangles in world space with a unit normal per vertex; shading interpolates the normals "
                   "(smooth shading; give flat faces their own vertices). Anisotropic models take the tangent "
                   "rule's t from the interpolated normal. The arrays are inline, or in a glTF 2.0 file the "
                   "object references: a mesh (its coordinates as they are) or a node (its mesh in the node's "
                   "world transform), all its triangle primitives or one; normals as facet import-gltf reads "
                   "them (a primitive without NORMAL is flat-shaded, zero-area triangles dropped). A file "
                   "several objects reference is read once.");
    m.params = {text("name", "a name for reports"), text("material", "a key of the scene's \"materials\""),
                list("positions", "vertex positions, world space", ParamKind::Points),
                list("normals", "a normal per vertex, world space", ParamKind::Points, true),
                list("triangles", "vertex indices, counter-clockwise seen from the normals' side",
                     ParamKind::Triangles),
                list("texcoords", "texture coordinates set 0 per vertex, [u, v] (glTF's TEXCOORD_0: v down the "
                                  "picture; docs/textures.md)", ParamKind::Points),
                list("texcoords1", "texture coordinates set 1 per vertex (glTF's TEXCOORD_1)", ParamKind::Points),
                list("tangents", "a tangent per vertex, [x, y, z, w] (glTF's TANGENT): a normal map's ∂p/∂u and "
                                 "its bitangent B = w·(n × t), w = +1 or −1; absent: facet computes MikkTSpace "
                                 "tangents (docs/textures.md)",
                     ParamKind::Points, true),
                list("colors", "a vertex colour per vertex, [r, g, b, a] linear (glTF's COLOR_0; a = 1 for an "
                               "RGB colour): the values of its material that take \"vertex_color\" multiply by it, "
                               "blended across each triangle as the texture coordinates are; absent: white "
                               "(docs/textures.md)",
                     ParamKind::Points),
                text("gltf", "a glTF 2.0 file (.gltf or .glb), relative to the scene file"),
                index("mesh", "the glTF file's mesh: its index in \"meshes\" or its name", true),
                index("node", "the glTF file's node: its index in \"nodes\" or its name; its mesh in its world "
                              "transform", true),
                index("primitive", "the index of one primitive of the mesh; absent: every triangle primitive",
                      false),
                index("texcoord0", "which glTF TEXCOORD_n the mesh's texture coordinate set 0 is (default 0): "
                                   "import-gltf names the sets a material reads beyond 0 and 1",
                      false),
                index("texcoord1", "which glTF TEXCOORD_n the mesh's texture coordinate set 1 is (default 1)", false)};
    for (auto& p : m.params) {
      p.required = false;  // the forms say which keys a mesh needs
      if (p.name == "texcoords" || p.name == "texcoords1") p.arity = 2;
      if (p.name == "tangents") p.arity = 4;
      if (p.name == "colors") p.arity = 4, p.range = Range::color();
    }
    m.forms = {{"inline arrays", {"positions", "normals", "triangles"}, {"texcoords", "texcoords1", "tangents", "colors"}},
               {"a glTF file's mesh", {"gltf", "mesh"}, {"primitive", "texcoord0", "texcoord1"}},
               {"a glTF file's node", {"gltf", "node"}, {"primitive", "texcoord0", "texcoord1"}}};
    m.object_type = ObjectType::Mesh;
    all.push_back(m);
  }
}

}  // namespace facet::catalog_detail
