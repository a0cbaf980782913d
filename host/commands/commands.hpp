// Each carbtf subcommand registers itself on the application; the callback runs the command.
#pragma once

#include <CLI/CLI.hpp>

namespace carbtf::cli {

// Every command below, in the order `carbtf --help` lists them, then check_every_option() over them: the
// whole command line as main() builds it.
void register_all_commands(CLI::App& app);

void register_devices_command(CLI::App& app);
void register_noise_command(CLI::App& app);
void register_demo_command(CLI::App& app);
void register_bench_command(CLI::App& app);
void register_bench_analyze_command(CLI::App& bench);   // under `bench`
void register_bench_data_command(CLI::App& bench);      // under `bench`
void register_bench_synth_command(CLI::App& bench);     // under `bench`
void register_bench_fidelity_command(CLI::App& bench);  // under `bench`
void register_bench_frame_command(CLI::App& bench);     // under `bench`
void register_sample_command(CLI::App& app);
void register_info_command(CLI::App& app);
void register_analyze_command(CLI::App& app);
void register_normals_command(CLI::App& app);
void register_synth_command(CLI::App& app);
void register_conform_command(CLI::App& app);
void register_render_command(CLI::App& app);
void register_fidelity_command(CLI::App& app);

}  // namespace carbtf::cli
