// From a template to its DS model (paper §4.1: sweeps; §3.1: DS attributes).
#pragma once

#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Sweeps (`around`, `within`) and imports (`mesh`) every surface of the template into a DS
/// model: the skin first, then the others in template order; bounds computed. Runs the
/// model-level checks (check_model), then bends the model onto the template's spine
/// (spine_bend.h). Grains are not scattered here (variants do that).
/// @pre tmpl was returned by parse_template / load_template
/// @throws InputError for rules that need the swept surfaces (see model_checks.h, sweep.h)
DsModel build_model(const Template& tmpl);

}  // namespace cutaway
