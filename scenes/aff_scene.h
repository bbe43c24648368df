#pragma once
// AFF scenes (BART: Lext, Assarsson and Möller 2001) as kinray Scenes. Every mesh becomes an
// object; the keyframed transforms above it (and the camera's keyframes) are Kochanek-Bartels
// splines, which become piecewise-linear flightplans by sampling: at the scene's own frame times
// (`a start end frames`: frames evenly over [start, end]) or, with a keyrate, at start + k / rate
// and the end. docs/bart.md describes the format and what kinray makes of each element.
#include <filesystem>
#include <string>

#include "scenes/aff_document.h"
#include "scenes/scene.h"

namespace kinray {

/// True when `path` ends in .aff (any case).
[[nodiscard]] bool is_aff_file(const std::string& path);

/// The sample times of the animation: the frame times of `range`, or every 1 / keyrate seconds
/// from its start plus its end when keyrate > 0.
[[nodiscard]] std::vector<double> aff_sample_times(const AffRange& range, double keyrate);

/// Builds the scene of a parsed document; `source` names it in errors. Throws InputError (an
/// animated transform without keyframes, a scene without a view, ...).
[[nodiscard]] Scene build_aff_scene(const AffDocument& document, const std::string& source,
                                    double keyrate = 0);

/// parse_aff + build_aff_scene; the document's warnings go to warn() (util/warning.h), one each.
[[nodiscard]] Scene load_aff(const std::filesystem::path& path, double keyrate = 0);

}  // namespace kinray
