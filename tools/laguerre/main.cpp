// The `laguerre` command-line program: one executable, one subcommand per task.
#include <CLI/CLI.hpp>

#include <iostream>

#include "Commands.hpp"
#include "Common.hpp"
#include "Parallel.hpp"

int main(int argc, char** argv) {
  laguerre::tools::ParallelContext parallel(argc, argv);
  CLI::App app{"laguerre — greedy power routing over circle packings (Wormser 2008, Part IV).\n"
               "Run `laguerre COMMAND --help` for the options of a command."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "laguerre 0.1.0");
  using namespace laguerre::tools;
  Action pack = add_pack_command(app);
  Action route = add_route_command(app);
  Action table = add_thesis_table_command(app);
  Action generate = add_generate_command(app);
  Action simulate = add_simulate_command(app);
  Action live = add_live_command(app);
  Action run = add_run_command(app);
  Action compare = add_compare_command(app);
  Action diagram = add_diagram_command(app);
  Action mesh = add_mesh_command(app);
  Action mesh_quality = add_mesh_quality_command(app);
  return run_program(app, argc, argv, "laguerre", [&] {
    if (parallel.ranks() > 1 && !app.got_subcommand("simulate") && !app.got_subcommand("run") &&
        !app.got_subcommand("compare")) {
      std::cerr << "laguerre: only 'simulate', 'run' and 'compare' run across MPI ranks so far; run '"
                << app.get_subcommands().front()->get_name() << "' without mpirun (or with -np 1)\n";
      return 2;
    }
    if (app.got_subcommand("pack")) return pack();
    if (app.got_subcommand("route")) return route();
    if (app.got_subcommand("thesis-table")) return table();
    if (app.got_subcommand("generate")) return generate();
    if (app.got_subcommand("simulate")) return simulate();
    if (app.got_subcommand("live")) return live();
    if (app.got_subcommand("run")) return run();
    if (app.got_subcommand("compare")) return compare();
    if (app.got_subcommand("diagram")) return diagram();
    if (app.got_subcommand("mesh")) return mesh();
    if (app.got_subcommand("mesh-quality")) return mesh_quality();
    return 0;
  });
}
