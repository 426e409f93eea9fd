// latsim schema: every scenario key, as a JSON Schema or the Markdown reference.
#include <CLI/CLI.hpp>

#include <cstdio>

#include "commands.hpp"
#include "latsim/run/runner.hpp"
#include "latsim/scenario/schema.hpp"

namespace latsim::app {

int command_schema(int argc, char** argv) {
  CLI::App app{"Print every scenario key with its type, default, range, unit and meaning", "latsim schema"};
  std::string format = "json-schema";
  app.add_option("--format", format, "json-schema (for editors and validators) or markdown (the reference)")
      ->check(CLI::IsMember({"json-schema", "markdown"}))
      ->capture_default_str();
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  const scenario::ObjectSchema schema = run::scenario_schema();
  if (format == "markdown") std::fputs(scenario::markdown_reference(schema).c_str(), stdout);
  else std::printf("%s\n", scenario::json_schema(schema).dump(2).c_str());
  return kExitOk;
}

}  // namespace latsim::app
