#pragma once
// Mesh sequences: simulators write one mesh file per frame (PLY or OBJ). A SCENE that is a folder
// of such files, or a glob over them ('sim/frame_*.ply'), becomes one object per mesh (per OBJ
// object or group) with one key per file, in the natural order of the file names, at --keyrate
// keys per second (default 24). Every file must share the first file's topology. The readers keep
// double precision (docs/mesh_sequences.md).
#include <string>
#include <string_view>
#include <vector>

#include "scenes/model_import.h"
#include "scenes/scene.h"

namespace kinray {

/// The key rate of a sequence when --keyrate is not given.
inline constexpr double kSequenceKeyrate = 24;

/// True when `spec` names a mesh sequence: an existing folder, or a name holding a wildcard
/// (*, ?, [) that is not itself an existing file.
[[nodiscard]] bool is_mesh_sequence(const std::string& spec);

/// Natural order of file names: digit runs compare as numbers ("frame_9" before "frame_10"),
/// everything else character by character; equal numbers of different spelling ("01", "1") fall
/// back to the plain order.
[[nodiscard]] bool natural_less(std::string_view a, std::string_view b);

/// The files of the sequence `spec`, in natural order of their names. Throws InputError naming
/// `spec` when it names no .ply or .obj file, mixes the two formats, or the glob matches a file of
/// another kind.
[[nodiscard]] std::vector<std::string> mesh_sequence_files(const std::string& spec);

/// Loads the sequence `spec` (options.keyrate: keys per second, 0 for kSequenceKeyrate; the
/// camera is automatic framing). Throws InputError naming the file at fault: a malformed file
/// (file:line), or one whose topology differs from the first file's, and what differs.
[[nodiscard]] Scene load_mesh_sequence(const std::string& spec, const ModelOptions& options = {});

}  // namespace kinray
