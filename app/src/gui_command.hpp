#pragma once
// `sutura gui [SESSION] [--out DIR] [--record FILE] [--script FILE]`: the interactive window.
#include <CLI/CLI.hpp>

#include "sutura/ui/gui.hpp"

namespace sutura::app {

/// Adds the `gui` subcommand to `app`, filling `options` when parsed.
CLI::App* add_gui_command(CLI::App& app, ui::GuiOptions& options);

}  // namespace sutura::app
