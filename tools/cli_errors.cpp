#include "tools/cli_errors.h"

#include <string>
#include <utility>
#include <vector>

namespace kinray {
namespace {

/// The subcommand being parsed (the deepest one that was given), else the app itself.
const CLI::App& active_command(const CLI::App& app) {
  for (const CLI::App* command : app.get_subcommands())
    if (command->parsed()) return active_command(*command);
  return app;
}

std::string help_hint(const CLI::App& command) {
  std::string path = command.get_name();
  for (const CLI::App* parent = command.get_parent(); parent; parent = parent->get_parent())
    path = parent->get_name() + " " + path;
  return "see " + path + " --help";
}

/// What an option's value must look like, from the type CLI11 converts it to.
std::string expected_value(const CLI::App& command, const std::string& name) {
  const CLI::Option* option = command.get_option_no_throw(name);
  const std::string type = option ? option->get_type_name() : "";
  if (type.rfind("INT", 0) == 0 || type.rfind("UINT", 0) == 0) return "a whole number";
  if (type.rfind("FLOAT", 0) == 0) return "a number";
  if (type.rfind("BOOLEAN", 0) == 0) return "nothing (it is a flag) or true/false";
  return "a value of the form the help shows";
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

/// A value as echoed back in a message: at most 40 characters (a 300-digit number is cut).
std::string echoed(const std::string& value) {
  return value.size() <= 40 ? value : value.substr(0, 37) + "...";
}

/// Why CLI11 could not convert `value` to the option's type: a whole number that does not fit
/// the type is out of range, not malformed.
std::string conversion_problem(const CLI::App& command, const std::string& name,
                               const std::string& value) {
  const std::string expected = expected_value(command, name);
  const std::string digits =
      starts_with(value, "-") || starts_with(value, "+") ? value.substr(1) : value;
  const bool whole = !digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos;
  if (expected == "a whole number" && whole)
    return "'" + echoed(value) + "' is out of range (too large a whole number)";
  return "expected " + expected + ", got '" + echoed(value) + "'";
}

/// The words after `prefix` in `message`, in command-line order (CLI11 lists extras reversed).
std::vector<std::string> listed_arguments(const std::string& message, const std::string& prefix) {
  std::vector<std::string> words;
  const size_t start = message.find(prefix);
  if (start == std::string::npos) return words;
  std::string rest = message.substr(start + prefix.size());
  for (size_t begin = 0; begin < rest.size();) {
    const size_t end = std::min(rest.find(' ', begin), rest.size());
    if (end > begin) words.insert(words.begin(), rest.substr(begin, end - begin));
    begin = end + 1;
  }
  return words;
}

InputError unexpected_arguments(const CLI::App& command, const std::string& message) {
  std::vector<std::string> words = listed_arguments(
      message, message.find("arguments were") != std::string::npos ? "arguments were not expected: "
                                                                   : "argument was not expected: ");
  for (const std::string& word : words)
    if (starts_with(word, "-"))
      return InputError(
          word, "no such flag for '" + command.get_name() + "' (" + help_hint(command) + ")");
  const std::string first = words.empty() ? message : words.front();
  return InputError(command.get_name(), "unexpected argument '" + first + "' (" +
                                            help_hint(command) + "; quote a path with spaces)");
}

}  // namespace

InputError name_the_flag(const OptionError& error) {
  // The fields the library can reject, and their flags: BackendConfig's (renderer/backends/backend.h),
  // RenderParams' (renderer/job/render_job.h) and FrameScheduleParams' (renderer/job/frame_schedule.h).
  // Enum fields cannot hold a bad value, their flags refuse one at parse time.
  static const std::pair<const char*, const char*> kFlags[] = {
      {"width", "--size"},
      {"threads", "--threads"},
      {"embree_packet", "--packet"},
      {"packet", "--packet"},
      {"shutter", "--shutter"},
      {"backend", "--backend"},
      {"aov", "--aov"},
      {"keyrate", "--keyrate"},
      {"video", "--video"},
      {"lights", "--light"},
      {"frames", "--frames"},
      {"fps", "--fps"},
      {"inbetweens", "--inbetweens"},
      {"time", "--time"},
      {"chunk", "--chunk"},
      {"frame_range", "--frame-range"},
      {"frame_slice", "--chunk/--frame-range"},
      {"aa_samples", "--aa-samples"},
      {"aa", "--aa"},
  };
  for (const auto& [field, flag] : kFlags)
    if (error.where() == field) return InputError(flag, error.message());
  return error;
}

InputError explain_parse_error(const CLI::App& app, const CLI::ParseError& error) {
  const CLI::App& command = active_command(app);
  const std::string message = error.what();
  const std::string hint = " (" + help_hint(command) + ")";
  if (dynamic_cast<const CLI::ConversionError*>(&error)) {
    // "Could not convert: --frames = many"
    const std::string prefix = "Could not convert: ";
    const size_t equals = message.find(" = ");
    if (starts_with(message, prefix) && equals != std::string::npos) {
      const std::string name = message.substr(prefix.size(), equals - prefix.size());
      return InputError(name, conversion_problem(command, name, message.substr(equals + 3)));
    }
    const size_t colon = message.find(": ");
    if (colon != std::string::npos)  // "--audit: too many inputs for a flag"
      return InputError(message.substr(0, colon), "is a flag and takes no value");
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
    const size_t colon = message.find(':');
    if (message.find("At Most") != std::string::npos && colon != std::string::npos)
      return InputError(message.substr(0, colon), "given more than once; give it once");
    const size_t to = message.find(" arguments to ");
    if (to != std::string::npos) {  // "Expected exactly 1 arguments to --frames, got 0"
      const size_t comma = message.find(',', to);
      return InputError(message.substr(to + 14, comma - to - 14), "needs a value" + hint);
    }
    if (colon != std::string::npos)  // "--size: 1 required TEXT missing"
      return InputError(message.substr(0, colon), "needs a value" + hint);
  }
  if (dynamic_cast<const CLI::ValidationError*>(&error)) {
    const size_t colon = message.find(": ");  // "--out: the path is empty"
    if (colon != std::string::npos)
      return InputError(message.substr(0, colon), message.substr(colon + 2));
  }
  if (dynamic_cast<const CLI::ExtrasError*>(&error)) return unexpected_arguments(command, message);
  if (dynamic_cast<const CLI::ExcludesError*>(&error)) {
    const size_t at = message.find(" excludes ");  // "--frames excludes --fps"
    if (at != std::string::npos)
      return InputError(message.substr(0, at),
                        "cannot be given together with " + message.substr(at + 10));
  }
  if (dynamic_cast<const CLI::RequiredError*>(&error)) {
    if (&command == &app) return InputError("", "no command given (see kinray --help)");
    const size_t at = message.find(" is required");
    if (at != std::string::npos) return InputError(message.substr(0, at), "missing" + hint);
  }
  if (dynamic_cast<const CLI::RequiresError*>(&error)) {
    const size_t at = message.find(" requires ");
    if (at != std::string::npos)
      return InputError(message.substr(0, at), "needs " + message.substr(at + 10) + " too");
  }
  return InputError(command.get_name(), message + hint);
}

}  // namespace kinray
