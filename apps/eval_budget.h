// apps/eval_budget.h — `footprint eval --budget`: where a filtered mode's error comes from.
//
//   footprint eval --budget [SCENE...] --out DIR [--budget-filter fa-rough] [--reference-spp N]
//                  [--size W] [--threads N] [--quiet]
//
// For each scene it renders render/error_budget.h's images — the reference (N samples), the mode
// at 1 spp and one hybrid per term (the mode with that term taken from the reference's samples) —
// and reports each one's RMSE against the reference over the interior mask (renderer.h) and over
// all pixels, and the share of the mode's interior error the term removes, 1 − RMSE_term/RMSE_mode.
// Prints the table, writes DIR/budget.csv and DIR/budget.json (one row per scene and term) and the
// images as DIR/<scene>/budget_<term>.png. Returns 0, or 1 after one line "footprint: …"; a run
// that fails leaves none of its files behind.
#pragma once

#include "eval_command.h"

namespace footprint {

int run_error_budget_command(const EvalCommandOptions& options);

}  // namespace footprint
