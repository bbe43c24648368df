#include "tools/option_scope.h"

#include <algorithm>
#include <cctype>

#include "scenes/procedural.h"
#include "util/input_error.h"

namespace kinray {
namespace {

void require_backend(std::span<const std::string> backends, const char* backend, const char* flag,
                     const std::string& used) {
  if (std::find(backends.begin(), backends.end(), backend) != backends.end()) return;
  std::string list;
  for (const std::string& name : backends) list += (list.empty() ? "" : " and ") + name;
  throw InputError(flag, "applies to the " + std::string(backend) + " backend only, and this " +
                             "command runs " + list + " (" + used + " would be ignored)");
}

bool is_model_spec(const std::string& scene) {
  const std::string name = scene.substr(0, scene.find(':'));
  if (is_builtin_scene(name)) return false;
  const std::string lower = [&] {
    std::string text = scene;
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
  }();
  return !(lower.size() >= 5 && lower.compare(lower.size() - 5, 5, ".json") == 0);
}

}  // namespace

void check_options_apply(const RenderParams& params, std::span<const std::string> backends) {
  const RenderParams defaults;
  if (params.packet != defaults.packet)
    require_backend(backends, "embree", "--packet", "--packet " + std::to_string(params.packet));
  if (params.embree_mode != defaults.embree_mode)
    require_backend(backends, "embree", "--embree-mode", "--embree-mode " + std::string(embree_build_name(params.embree_mode)));
  if (params.sort != defaults.sort)
    require_backend(backends, "kinetic", "--sort", "--sort " + std::string(depth_sort_name(params.sort)));
  if (params.audit) require_backend(backends, "kinetic", "--audit", "--audit");
  if (params.shadow_tree != defaults.shadow_tree)
    require_backend(backends, "kinetic", "--shadow-tree",
                    "--shadow-tree " + std::string(shadow_tree_name(params.shadow_tree)));
  if (is_model_spec(params.scene)) return;
  const char* what = is_builtin_scene(params.scene.substr(0, params.scene.find(':')))
                         ? "a built-in scene"
                         : "a .json scene file";
  if (!params.animation.empty())
    throw InputError("--animation", "applies to model files only, and '" + params.scene + "' is " +
                                        what + " (it has one animation)");
  if (params.keyrate != defaults.keyrate)
    throw InputError("--keyrate", "applies to model files only, and '" + params.scene + "' is " +
                                      what + " (a built-in takes keyrate= as a parameter)");
}

}  // namespace kinray
