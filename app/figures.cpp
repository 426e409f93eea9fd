// latsim figures: the figure registry, as JSON or as Markdown tables.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "commands.hpp"
#include "latsim/results/figure_registry.hpp"

namespace latsim::app {

namespace {

std::string joined(const std::vector<std::string>& words, const char* empty) {
  if (words.empty()) return empty;
  std::string out;
  for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

void print_markdown(const results::FigureRegistry& registry) {
  std::printf("# Figures\n\n| figure | kind | unit | family | pipelines | meaning |\n| --- | --- | --- | --- | --- | --- |\n");
  for (const results::FigureDecl& d : registry.figures())
    std::printf("| `%s` | %s | %s | %s | %s | %s |\n", d.name.c_str(), d.kind.c_str(), d.unit.c_str(), d.family.c_str(),
                joined(d.pipelines, "any").c_str(), d.meaning.c_str());
  std::printf("\n# Headlines\n\n| headline | used by | figures, in rank order | why |\n| --- | --- | --- | --- |\n");
  for (const auto& [set, about] : registry.headlines())
    std::printf("| `%s` | %s | %s | %s |\n", set.c_str(), about.used_by.c_str(), joined(registry.headline(set), "").c_str(),
                about.why.c_str());
  std::printf("\n# Columns of results.csv and the report's tables\n\n| column | figure | label |\n| --- | --- | --- |\n");
  for (const results::FigureColumn& c : registry.columns())
    std::printf("| `%s` | `%s` | %s |\n", c.name.c_str(), c.figure.c_str(), c.label.c_str());
}

}  // namespace

int command_figures(int argc, char** argv) {
  CLI::App app{"Print every figure a run may report, as the figure registry declares it (results/figure_registry.json)",
               "latsim figures"};
  std::string format = "markdown";
  app.add_option("--format", format, "markdown (tables of figures, headlines and columns) or json (the registry)")
      ->check(CLI::IsMember({"markdown", "json"}))
      ->capture_default_str();
  if (const auto rc = parse_options(app, argc, argv)) return *rc;
  if (format == "json") std::fputs(std::string(results::FigureRegistry::builtin_text()).c_str(), stdout);
  else print_markdown(results::FigureRegistry::builtin());
  return kExitOk;
}

}  // namespace latsim::app
