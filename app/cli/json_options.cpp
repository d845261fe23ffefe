#include <algorithm>
#include <string>

#include "app/cli/commands.hpp"

namespace gr {

void set_options_from_json(CLI::App& command, const nlohmann::json& object) {
  const std::string& name_of_command = command.get_name();
  if (!object.is_object())
    throw CLI::ValidationError(name_of_command + " options", "must be an object");
  for (const auto& [key, value] : object.items()) {
    std::string name = "--" + key;
    std::replace(name.begin(), name.end(), '_', '-');
    CLI::Option* option = command.get_option_no_throw(name);
    if (option == nullptr || name == "--help")
      throw CLI::ValidationError(name, "not a " + name_of_command +
                                           " option (see garment-retarget " + name_of_command +
                                           " --help)");
    if (option->get_expected_max() == 0) {
      if (!value.is_boolean()) throw CLI::ValidationError(name, "a flag: give true or false");
      if (!value.get<bool>()) continue;  // a flag left out
      option->add_result(option->get_flag_value(name, ""));
    } else {
      const auto add = [&](const nlohmann::json& item) {
        if (item.is_string())
          option->add_result(item.get<std::string>());
        else if (item.is_number())
          option->add_result(item.dump());
        else
          throw CLI::ValidationError(name, "needs a number or a text");
      };
      if (value.is_array()) {
        for (const nlohmann::json& item : value) add(item);
      } else {
        add(value);
      }
    }
    option->run_callback();
  }
  for (const CLI::Option* option : command.get_options())
    if (option->get_required() && option->count() == 0)
      throw CLI::RequiredError(option->get_name());
}

}  // namespace gr
