#include "latsim/sweep/results_db.hpp"

#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <map>
#include <memory>
#include <stdexcept>

#include <sqlite3.h>

namespace latsim::sweep {

namespace {

using Json = nlohmann::json;
namespace fs = std::filesystem;

/// An open SQLite database that closes itself; every failure throws with the file name.
class Database {
 public:
  explicit Database(const fs::path& file) : file_(file) {
    if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, nullptr) != SQLITE_OK) {
      const std::string message = db_ ? sqlite3_errmsg(db_) : "out of memory";
      sqlite3_close(db_);
      throw std::runtime_error(file.string() + ": cannot create database: " + message);
    }
  }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;
  ~Database() { sqlite3_close(db_); }

  void exec(const std::string& sql) {
    char* error = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
      const std::string message = error ? error : "unknown error";
      sqlite3_free(error);
      fail(message);
    }
  }
  sqlite3* handle() { return db_; }
  [[noreturn]] void fail(const std::string& message) const {
    throw std::runtime_error(file_.string() + ": " + message);
  }

 private:
  fs::path file_;
  sqlite3* db_ = nullptr;
};

/// A prepared INSERT whose parameters are bound by position and reset after each row.
class Insert {
 public:
  Insert(Database& db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      db.fail(sqlite3_errmsg(db.handle()));
  }
  Insert(const Insert&) = delete;
  Insert& operator=(const Insert&) = delete;
  ~Insert() { sqlite3_finalize(stmt_); }

  /// Binds without a copy: `v` must live until run() (every caller's string
  /// does: a record's, its flattened figures', or one inside its summary).
  Insert& text(const std::string& v) {
    sqlite3_bind_text(stmt_, ++param_, v.c_str(), static_cast<int>(v.size()), SQLITE_STATIC);
    return *this;
  }
  /// Binds a copy, for a string about to go.
  Insert& text_copy(const std::string& v) {
    sqlite3_bind_text(stmt_, ++param_, v.c_str(), static_cast<int>(v.size()), SQLITE_TRANSIENT);
    return *this;
  }
  Insert& integer(int64_t v) {
    sqlite3_bind_int64(stmt_, ++param_, v);
    return *this;
  }
  Insert& real(double v) {
    sqlite3_bind_double(stmt_, ++param_, v);
    return *this;
  }
  Insert& null() {
    sqlite3_bind_null(stmt_, ++param_);
    return *this;
  }
  /// Binds a JSON value with its own SQLite type: numbers stay numbers, strings text.
  Insert& value(const Json& v) {
    if (v.is_number_integer()) return integer(v.get<int64_t>());
    if (v.is_number()) return real(v.get<double>());
    if (v.is_boolean()) return integer(v.get<bool>() ? 1 : 0);
    if (v.is_string()) return text(v.get_ref<const std::string&>());
    if (v.is_null()) return null();
    return text_copy(v.dump());
  }
  Insert& optional_number(const Json& object, const char* key) {
    return object.contains(key) && object[key].is_number() ? value(object[key]) : null();
  }
  void run() {
    if (sqlite3_step(stmt_) != SQLITE_DONE) db_.fail(sqlite3_errmsg(db_.handle()));
    // Every row binds every parameter again, so the old bindings need no clearing.
    sqlite3_reset(stmt_);
    param_ = 0;
  }

 private:
  Database& db_;
  sqlite3_stmt* stmt_ = nullptr;
  int param_ = 0;
};

std::string quoted_identifier(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The statistics every distribution figure has, one column each.
constexpr const char* kStats[] = {"count", "mean", "stddev", "min", "p50", "p90", "p99", "p999", "max"};

// A few tens of rows a run, each of integers and reals: the names are stored
// once (names) and the run by its plan index (runs.plan_index), and each
// distribution is one row of its statistics; the views give run ids and names
// as text, and the statistics as rows.
void create_tables(Database& db, const std::vector<std::string>& axis_pointers) {
  std::string runs = "CREATE TABLE runs (run_id TEXT PRIMARY KEY, plan_index INTEGER UNIQUE, point INTEGER, "
                     "seed INTEGER, replication INTEGER, events INTEGER, wall_s REAL, peak_rss_mb REAL, fingerprint TEXT";
  for (const auto& pointer : axis_pointers) runs += ", " + quoted_identifier(pointer);
  db.exec(runs + ");");
  std::string columns, unpivot;
  for (const char* stat : kStats) {
    columns += std::string(", ") + stat + " REAL";
    unpivot += std::string(unpivot.empty() ? "" : " UNION ALL ") + "SELECT r.run_id, n.name, '" + stat + "', d." +
               stat + " FROM distribution_values d JOIN runs r USING (plan_index) JOIN names n ON n.name_id = "
               "d.name_id WHERE d." + stat + " IS NOT NULL";
  }
  db.exec("CREATE TABLE axes (axis INTEGER, pointer TEXT);"
          "CREATE TABLE names (name_id INTEGER PRIMARY KEY, name TEXT UNIQUE);"
          "CREATE TABLE figure_values (plan_index INTEGER, name_id INTEGER, value REAL);"
          "CREATE TABLE distribution_values (plan_index INTEGER, name_id INTEGER" + columns + ");"
          // Statistics beyond the usual nine (none today), so that nothing is lost.
          "CREATE TABLE distribution_extras (plan_index INTEGER, name_id INTEGER, stat_id INTEGER, value REAL);"
          "CREATE TABLE model_values (plan_index INTEGER, model_id INTEGER, events INTEGER, wall_s REAL);"
          "CREATE VIEW figures (run_id, name, value) AS SELECT r.run_id, n.name, f.value FROM figure_values f "
          "JOIN runs r USING (plan_index) JOIN names n ON n.name_id = f.name_id;"
          "CREATE VIEW distributions (run_id, name, stat, value) AS " + unpivot +
          " UNION ALL SELECT r.run_id, n.name, s.name, d.value FROM distribution_extras d JOIN runs r USING "
          "(plan_index) JOIN names n ON n.name_id = d.name_id JOIN names s ON s.name_id = d.stat_id;"
          "CREATE VIEW models (run_id, model, events, wall_s) AS SELECT r.run_id, n.name, m.events, m.wall_s FROM "
          "model_values m JOIN runs r USING (plan_index) JOIN names n ON n.name_id = m.model_id;");
}

/// Ids of the names in `names`, given out in order of first use.
class NameIds {
 public:
  explicit NameIds(Database& db) : insert_(db, "INSERT INTO names VALUES (?, ?);") {}
  int64_t of(const std::string& name) {
    const auto [it, fresh] = ids_.emplace(name, static_cast<int64_t>(ids_.size()));
    if (fresh) insert_.integer(it->second).text(it->first).run();
    return it->second;
  }

 private:
  Insert insert_;
  std::map<std::string, int64_t> ids_;
};

/// The prepared inserts of every table a run has rows in.
struct RunInserts {
  explicit RunInserts(Database& db, size_t axes)
      : run(db, "INSERT INTO runs VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?" + repeat(", ?", axes) + ");"),
        figure(db, "INSERT INTO figure_values VALUES (?, ?, ?);"),
        distribution(db, "INSERT INTO distribution_values VALUES (?, ?" + repeat(", ?", std::size(kStats)) + ");"),
        extra(db, "INSERT INTO distribution_extras VALUES (?, ?, ?, ?);"),
        model(db, "INSERT INTO model_values VALUES (?, ?, ?, ?);"),
        names(db) {}
  static std::string repeat(const char* text, size_t n) {
    std::string out;
    for (size_t i = 0; i < n; ++i) out += text;
    return out;
  }
  Insert run, figure, distribution, extra, model;
  NameIds names;
};

void insert_distribution(RunInserts& in, int64_t index, const Json& node, const std::string& name) {
  const int64_t name_id = in.names.of(name);
  in.distribution.integer(index).integer(name_id);
  for (const char* stat : kStats) in.distribution.optional_number(node, stat);
  in.distribution.run();
  for (auto it = node.begin(); it != node.end(); ++it) {
    if (!it.value().is_number() || std::find(std::begin(kStats), std::end(kStats), it.key()) != std::end(kStats))
      continue;
    in.extra.integer(index).integer(name_id).integer(in.names.of(it.key())).real(it.value().get<double>()).run();
  }
}

bool is_distribution(const Json& node) { return node.is_object() && node.contains("count") && node.contains("mean"); }

// Every number under `node`: scalars (booleans as 0 and 1) and distributions.
void insert_figures(RunInserts& in, int64_t index, const Json& node, const std::string& name) {
  if (node.is_number() || node.is_boolean()) {
    const double v = node.is_boolean() ? (node.get<bool>() ? 1.0 : 0.0) : node.get<double>();
    in.figure.integer(index).integer(in.names.of(name)).real(v).run();
  } else if (is_distribution(node)) {
    insert_distribution(in, index, node, name);
  } else if (node.is_object()) {
    for (auto it = node.begin(); it != node.end(); ++it)
      insert_figures(in, index, it.value(), name.empty() ? it.key() : name + "." + it.key());
  }
}

void insert_records(Database& db, const std::vector<std::string>& axis_pointers, const std::vector<RunRecord>& records) {
  RunInserts in(db, axis_pointers.size());
  for (size_t i = 0; i < records.size(); ++i) {
    const RunRecord& r = records[i];
    const Json& s = r.summary;
    const auto index = static_cast<int64_t>(i);
    in.run.text(r.run_id).integer(index).integer(static_cast<int64_t>(r.point));
    in.run.integer(static_cast<int64_t>(r.seed)).integer(static_cast<int64_t>(r.replication));
    in.run.optional_number(s, "events").optional_number(s, "wall_s").optional_number(s, "peak_rss_mb");
    if (s.contains("fingerprint") && s["fingerprint"].is_string()) in.run.text(s["fingerprint"].get_ref<const std::string&>());
    else in.run.null();
    for (const auto& v : r.values) in.run.value(v);
    in.run.run();
    if (const auto f = s.find("figures"); f != s.end()) insert_figures(in, index, *f, "");
    if (const auto m = s.find("models"); m != s.end() && m->is_object())
      for (auto it = m->begin(); it != m->end(); ++it)
        in.model.integer(index).integer(in.names.of(it.key())).optional_number(it.value(), "events")
            .optional_number(it.value(), "wall_s").run();
  }
}

}  // namespace

void write_results_db(const fs::path& file, const std::vector<std::string>& axis_pointers,
                      const std::vector<RunRecord>& records) {
  const fs::path temp = file.string() + ".tmp." + std::to_string(::getpid());
  std::error_code ignored;
  fs::remove(temp, ignored);
  try {
    {
      Database db(temp);
      // The file is private until renamed, so no journal is needed for atomicity.
      db.exec("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; BEGIN;");
      create_tables(db, axis_pointers);
      Insert axis(db, "INSERT INTO axes VALUES (?, ?);");
      for (size_t a = 0; a < axis_pointers.size(); ++a) axis.integer(static_cast<int64_t>(a)).text(axis_pointers[a]).run();
      insert_records(db, axis_pointers, records);
      db.exec("COMMIT;");
    }
    fs::rename(temp, file);
  } catch (...) {
    fs::remove(temp, ignored);
    throw;
  }
}

}  // namespace latsim::sweep
