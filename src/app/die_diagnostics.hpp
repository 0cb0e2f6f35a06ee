// The die-filling diagnostics (diagnostics/die_diagnostics.hpp) under the names the
// application layer uses for them: the phases and outputs of a run (particle_run,
// run_outputs, run_schedule) refer to them as app::DieDiagnostics and so on.
#pragma once
#include "diagnostics/die_diagnostics.hpp"

namespace cgdem::app {

using diagnostics::DiagnosticsRow;
using diagnostics::DiagnosticsSpec;
using diagnostics::DieDiagnostics;
using diagnostics::PathFlux;
using diagnostics::PressureCell;
using diagnostics::read_diagnostics;

}  // namespace cgdem::app
