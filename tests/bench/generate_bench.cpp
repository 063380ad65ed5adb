// Google Benchmark of facet's own code generation: generate() for every target
// and every lobe model of the catalog at its defaults (facet::model_materials()),
// one benchmark each ("generate/<target>/<model>"), plus the whole catalog per
// target ("catalog/<target>"). What is timed is what `facet generate` does after
// reading the file: compiling the material to IR and printing the target.
//
//   build/bin/facet_generate_bench
//   build/bin/facet_generate_bench --benchmark_filter='generate/glsl/'
#include <benchmark/benchmark.h>

#include "catalog/material.h"
#include "targets/targets.h"

namespace {

using facet::GenerateOptions;
using facet::Material;
using facet::Target;

GenerateOptions options(Target t) {
  GenerateOptions o;
  o.target = t;
  o.source = "the catalog";
  return o;
}

void generate_one(benchmark::State& state, const Material& m, Target t) {
  const GenerateOptions o = options(t);
  size_t bytes = 0;
  for (auto _ : state) {
    std::string code = facet::generate(m, o);
    bytes += code.size();
    benchmark::DoNotOptimize(code);
  }
  state.SetBytesProcessed(int64_t(bytes));
}

void generate_catalog(benchmark::State& state, const std::vector<Material>& ms, Target t) {
  const GenerateOptions o = options(t);
  for (auto _ : state)
    for (const auto& m : ms) {
      std::string code = facet::generate(m, o);
      benchmark::DoNotOptimize(code);
    }
  state.SetItemsProcessed(int64_t(state.iterations() * ms.size()));  // materials per second
}

}  // namespace

int main(int argc, char** argv) {
  static const std::vector<Material> models = facet::model_materials();
  for (Target t : facet::all_targets()) {
    const std::string target = facet::target_name(t);
    for (const auto& m : models)
      benchmark::RegisterBenchmark(("generate/" + target + "/" + m.name).c_str(), generate_one, m, t)
          ->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark(("catalog/" + target).c_str(), generate_catalog, models, t)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
