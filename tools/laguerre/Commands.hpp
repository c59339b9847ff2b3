#pragma once
/// @file
/// Subcommands of the `laguerre` program: each registers its options on a CLI11 app and runs.

#include <CLI/CLI.hpp>

#include <functional>

namespace laguerre::tools {

/// A registered subcommand's action, run after parsing; returns the process exit code.
using Action = std::function<int()>;

/// `laguerre pack GRAPH …`: greedy power embedding, JSON and picture.
Action add_pack_command(CLI::App& app);
/// `laguerre route GRAPH-or-EMBEDDING …`: routing table over pairs.
Action add_route_command(CLI::App& app);
/// `laguerre simulate …`: the distributed protocol in the discrete-event simulator.
Action add_simulate_command(CLI::App& app);
/// `laguerre live …`: the distributed protocol over UDP on 127.0.0.1, in several processes.
Action add_live_command(CLI::App& app);
/// `laguerre generate …`: random graphs of the documented families.
Action add_generate_command(CLI::App& app);
/// `laguerre thesis-table …`: the experiment of thesis §5.4.1.
Action add_thesis_table_command(CLI::App& app);
/// `laguerre run SCENARIO.yaml …`: a scenario file's runs, results and pictures.
Action add_run_command(CLI::App& app);
/// `laguerre compare SCENARIO.yaml…`: routing schemes compared over scenario sweeps.
Action add_compare_command(CLI::App& app);
/// `laguerre diagram --kind K SITES …`: the diagrams of thesis Part I, JSON and pictures.
Action add_diagram_command(CLI::App& app);
/// `laguerre mesh DOMAIN …`: anisotropic meshing under a metric field.
Action add_mesh_command(CLI::App& app);
/// `laguerre mesh-quality MESH --metric …`: the quality report of `mesh` for any Medit mesh.
Action add_mesh_quality_command(CLI::App& app);

}  // namespace laguerre::tools
