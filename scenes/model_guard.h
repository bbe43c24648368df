#pragma once
// assimp 5.2 crashes (SIGSEGV) on some malformed files, e.g. DirectX .x skin weights that index
// past the mesh's vertices, and a hostile file may make a loader loop or allocate without end.
// No try/catch survives that, so the importer first lets a forked child process read the file:
// only when the child finishes cleanly does the importer read it itself (assimp is
// deterministic), and a crash or a hang becomes an InputError instead of taking kinray down.
#include <functional>
#include <optional>
#include <string>

namespace kinray {

/// Runs `work` in a child process (fork). Returns nothing when it returned an empty string, and
/// otherwise why not: the text it returned, the signal that killed it, or that it ran longer than
/// `timeout_seconds` (it is then killed). When no child can be started, runs nothing and returns
/// nothing: the caller's own attempt then decides.
[[nodiscard]] std::optional<std::string> run_in_child(const std::function<std::string()>& work,
                                                      double timeout_seconds);

}  // namespace kinray
