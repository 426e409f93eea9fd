// latsim compare's files: compare.md (the table and one verdict line per
// quantity), compare.csv and compare_values.json (for the plots).
#include <cstdio>
#include <initializer_list>
#include <string_view>

#include <nlohmann/json.hpp>

#include "latsim/results/csv_text.hpp"
#include "latsim/sweep/compare.hpp"

namespace latsim::sweep {

namespace {

using results::csv_field;

std::string num(const std::optional<double>& v, const char* format = "%.4f") {
  if (!v) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, format, *v);
  return buf;
}

// Appends the parts to `out` (no temporary strings: GCC 12 warns of some).
void put(std::string& out, std::initializer_list<std::string_view> parts) {
  for (std::string_view p : parts) out.append(p);
}

}  // namespace

std::string compare_markdown(const Comparison& c) {
  std::string out;
  put(out, {"# Capture and run compared\n\n- capture: ", c.capture_text, "\n- run: ", c.run_text, "\n"});
  for (const std::string& n : c.notes) put(out, {"- ", n, "\n"});
  out += "\nPer quantity: count, mean, p50 and p99 of each side, and the two-sample Kolmogorov-Smirnov distance "
         "D = sup |F_capture - F_run| where both sides are samples (0: the same distribution; 1: disjoint). "
         "`standing` says how the run stands to the quantity: predicted, converted (the definitions differ and one "
         "side is converted), derived (from replayed values and the run's own model) are judged; replayed, input, "
         "differs and no counterpart are shown and left out of the verdict.\n\n"
         "| quantity | standing | capture column | n | mean | p50 | p99 | run column | n | mean | p50 | p99 | KS D |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const CompareRow& r : c.rows) {
    const auto& a = r.capture.stats;
    const auto& b = r.run.stats;
    put(out, {"| ", r.label, " | ", standing_name(r.standing), " | ", r.capture.column, " | ",
              std::to_string(a.count), " | ", num(a.mean), " | ", num(a.p50), " | ", num(a.p99), " | ", r.run.column,
              " | ", std::to_string(b.count), " | ", num(b.mean), " | ", r.run.total_only ? "" : num(b.p50), " | ",
              r.run.total_only ? "" : num(b.p99), " | ", num(r.ks), " |\n"});
  }
  out += "\n## Verdict\n\n";
  int judged = 0, agree = 0;
  for (const CompareRow& r : c.rows) {
    put(out, {"- ", r.label, ": ", r.verdict, "\n"});
    if (r.agrees) {
      ++judged;
      agree += *r.agrees ? 1 : 0;
    }
  }
  put(out, {"\n", std::to_string(agree), " of ", std::to_string(judged), " judged quantities agree.\n"});
  return out;
}

std::string compare_csv(const Comparison& c) {
  std::string out =
      "quantity,standing,capture_column,capture_count,capture_mean,capture_p50,capture_p99,run_column,run_count,"
      "run_mean,run_p50,run_p99,ks_distance,agrees,verdict\n";
  for (const CompareRow& r : c.rows) {
    const auto& a = r.capture.stats;
    const auto& b = r.run.stats;
    put(out, {r.key, ",", csv_field(standing_name(r.standing)), ",", csv_field(r.capture.column), ",",
              std::to_string(a.count), ",", num(a.mean, "%.9g"), ",", num(a.p50, "%.9g"), ",", num(a.p99, "%.9g"), ",",
              csv_field(r.run.column), ",", std::to_string(b.count), ",", num(b.mean, "%.9g"), ",", num(b.p50, "%.9g"),
              ",", num(b.p99, "%.9g"), ",",
              num(r.ks, "%.9g"), ",", r.agrees ? (*r.agrees ? "1" : "0") : "", ",", csv_field(r.verdict), "\n"});
  }
  return out;
}

std::string compare_values_json(const Comparison& c) {
  nlohmann::json j = nlohmann::json::array();
  for (const CompareRow& r : c.rows) {
    nlohmann::json row{{"key", r.key},
                       {"label", r.label},
                       {"standing", standing_name(r.standing)},
                       {"capture", r.capture.values},
                       {"run", r.run.values},
                       {"run_total_only", r.run.total_only}};
    if (r.ks) row["ks"] = *r.ks;
    j.push_back(std::move(row));
  }
  return j.dump() + "\n";
}

}  // namespace latsim::sweep
