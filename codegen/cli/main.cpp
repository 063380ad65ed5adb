// facet — the command line: every command is its own file (cli/command.h).
#include <iostream>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "core/diagnostics.h"
#include "core/io.h"

int main(int argc, char** argv) {
  using namespace facet;
  CLI::App app{"facet " FACET_VERSION
               " — one material description, equivalent GLSL, OSL and POV-Ray code, and a C++ reference.\n"};
  app.require_subcommand(1);
  app.footer(
      "Examples:\n"
      "  facet generate examples/materials/ggx.json --target glsl -o ggx.frag\n"
      "  facet generate examples/materials/oren_nayar.json --target pov -o oren.pov && \\\n"
      "    povray +Ioren.pov +Ooren.png +W256 +H256 -A +FN16 File_Gamma=1.0\n"
      "  echo '[{\"n\":[0,0,1],\"l\":[0,1,1],\"v\":[0,0,1]}]' | facet eval examples/materials/lambert.json\n"
      "  facet models\n"
      "Run 'facet <command> --help' for a command's options. Formulas: MODELS.md.");

  // In the order `facet --help` lists them.
  const std::vector<cli::Command> commands = {
      cli::generate_command(app), cli::eval_command(app),        cli::models_command(app),
      cli::render_command(app),   cli::validate_command(app),    cli::import_gltf_command(app),
      cli::export_gltf_command(app), cli::sweep_command(app),    cli::physics_command(app),
      cli::plot_command(app),     cli::docs_command(app),        cli::cost_command(app),
      cli::draw_shaders_command(app), cli::schema_command(app),
  };

  CLI11_PARSE(app, argc, argv);
  set_progress_sink([](const std::string& line) { std::cerr << line << "\n"; });

  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const InputError& err) {
    for (const auto& d : err.diagnostics()) std::cerr << "error: " << d.format() << "\n";
    return 1;
  } catch (const IoError& err) {
    std::cerr << "error: " << err.what() << "\n";
    return 1;
  }
  return 0;
}
