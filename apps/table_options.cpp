#include "table_options.h"

namespace pdd::cli {

void add_table_options(CLI::App* cmd, const std::shared_ptr<OptionValues>& values,
                       const std::function<bool(const std::string&)>& wanted) {
  for (const OptionSpec& spec : reconstruct_option_specs()) {
    if (!wanted(spec.name)) continue;
    const std::string flag = "--" + spec.name;
    const std::string name = spec.name;
    if (spec.kind == OptionSpec::Kind::kFlag) {
      cmd->add_flag_callback(flag, [values, name] { (*values)[name] = "true"; }, spec.help);
      continue;
    }
    CLI::Option* option = cmd->add_option_function<std::string>(
        flag, [values, name](const std::string& value) { (*values)[name] = value; }, spec.help);
    switch (spec.kind) {
      case OptionSpec::Kind::kChoice: option->check(CLI::IsMember(spec.choices)); break;
      case OptionSpec::Kind::kNumber: option->type_name("FLOAT"); break;
      case OptionSpec::Kind::kInteger: option->type_name("INT"); break;
      case OptionSpec::Kind::kSeed: option->type_name("UINT"); break;
      case OptionSpec::Kind::kSize: option->type_name("SIZE"); break;
      case OptionSpec::Kind::kText: option->type_name("TEXT"); break;
      case OptionSpec::Kind::kFlag: break;
    }
    if (!spec.default_text.empty()) option->default_str(spec.default_text);
  }
}

void apply_table_options(const OptionValues& values, ReconstructOptions& options) {
  for (const auto& [name, value] : values) set_reconstruct_option(options, name, value);
}

}  // namespace pdd::cli
