#pragma once
// Each subcommand registers itself on the app and sets the exit code when it runs.
#include <CLI/CLI.hpp>

namespace strictmin::cli {

void add_deform_command(CLI::App& app, int& exit_code);
void add_eval_command(CLI::App& app, int& exit_code);
void add_report_command(CLI::App& app, int& exit_code);
void add_demo_command(CLI::App& app, int& exit_code);
void add_interp_command(CLI::App& app, int& exit_code);
void add_param_command(CLI::App& app, int& exit_code);
void add_gparam_command(CLI::App& app, int& exit_code);
void add_quads_command(CLI::App& app, int& exit_code);

}  // namespace strictmin::cli
