// facet — the command line: every command is its own file (cli/command.h).
#include <filesystem>
#include <iostream>
#include <new>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "core/diagnostics.h"
#include "core/io.h"
#include "core/text.h"

int main(int argc, char** argv) {
  using namespace facet;
  CLI::App app{"facet " FACET_VERSION
               " — one material description, equivalent GLSL, OSL and POV-Ray code, and a C++ reference.\n"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "facet " FACET_VERSION, "Print facet's version (the CMake project's) and exit");
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

  std::vector<std::string> allowed;
  app.add_option("--allow-path", allowed,
                 "A folder from which the files a glTF names (buffers, images) and the textures a material or "
                 "scene file names may also be read; without it, only files inside the naming file's own folder "
                 "are (any command; may be repeated)")
      ->check(CLI::ExistingDirectory)
      ->type_name("DIR");
  // --allow-path may also follow the command's name and its files: each command hands the options
  // it does not know to this one.
  for (const auto& c : commands) c.app->fallthrough();

  CLI11_PARSE(app, argc, argv);
  for (const auto& dir : allowed) allow_folder(dir);
  set_progress_sink([](const std::string& line) { std::cerr << line << "\n"; });

  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const InputError& err) {
    for (const auto& d : err.diagnostics()) std::cerr << "error: " << printable_lines(d.format()) << "\n";
    return 1;
  } catch (const IoError& err) {
    std::cerr << "error: " << printable_lines(err.what()) << "\n";
    return 1;
  } catch (const std::filesystem::filesystem_error& err) {  // a folder facet could not make, list or remove
    std::cerr << "error: " << printable_lines(err.what()) << "\n";
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "error: out of memory\n";
    return 1;
  }
  return 0;
}
