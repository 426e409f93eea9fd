#include "latsim/sweep/results_db.hpp"

#include <unistd.h>

#include <functional>
#include <memory>
#include <optional>
#include <unordered_map>
#include <stdexcept>

#include <sqlite3.h>

#include "latsim/des/random.hpp"

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
  Insert& optional_real(const std::optional<double>& v) { return v ? real(*v) : null(); }
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

/// A query whose rows are read one by one.
class Statement {
 public:
  Statement(Database& db, const std::string& sql) : db_(db) {
    if (sqlite3_prepare_v2(db.handle(), sql.c_str(), -1, &stmt_, nullptr) != SQLITE_OK)
      db.fail(sqlite3_errmsg(db.handle()));
  }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;
  ~Statement() { sqlite3_finalize(stmt_); }
  /// Moves to the next row; false when there is none.
  bool step() {
    const int rc = sqlite3_step(stmt_);
    if (rc != SQLITE_ROW && rc != SQLITE_DONE) db_.fail(sqlite3_errmsg(db_.handle()));
    return rc == SQLITE_ROW;
  }
  std::string text(int column) const {
    const auto* t = reinterpret_cast<const char*>(sqlite3_column_text(stmt_, column));
    return t ? t : "";
  }

 private:
  Database& db_;
  sqlite3_stmt* stmt_ = nullptr;
};

std::string quoted_identifier(const std::string& name) {
  std::string q = "\"";
  for (char c : name) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// A few tens of rows a run, each of integers and reals: the names are stored
// once (names) and the run by its plan index (runs.plan_index), and each
// distribution is one row of its statistics; the views give run ids and names
// as text, and the statistics as rows.
void create_tables(Database& db, const std::vector<std::string>& axis_pointers, bool views) {
  std::string runs = "CREATE TABLE runs (run_id TEXT PRIMARY KEY, plan_index INTEGER UNIQUE, point INTEGER, "
                     "seed INTEGER, replication INTEGER, events INTEGER, wall_s REAL, peak_rss_mb REAL, fingerprint TEXT";
  for (const auto& pointer : axis_pointers) runs += ", " + quoted_identifier(pointer);
  db.exec(runs + ");");
  std::string columns, unpivot;
  for (const char* stat : kDistributionStats) {
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
          "CREATE TABLE model_values (plan_index INTEGER, model_id INTEGER, events INTEGER, wall_s REAL);");
  if (!views) return;
  db.exec("CREATE VIEW figures (run_id, name, value) AS SELECT r.run_id, n.name, f.value FROM figure_values f "
          "JOIN runs r USING (plan_index) JOIN names n ON n.name_id = f.name_id;"
          "CREATE VIEW distributions (run_id, name, stat, value) AS " + unpivot +
          " UNION ALL SELECT r.run_id, n.name, s.name, d.value FROM distribution_extras d JOIN runs r USING "
          "(plan_index) JOIN names n ON n.name_id = d.name_id JOIN names s ON s.name_id = d.stat_id;"
          "CREATE VIEW models (run_id, model, events, wall_s) AS SELECT r.run_id, n.name, m.events, m.wall_s FROM "
          "model_values m JOIN runs r USING (plan_index) JOIN names n ON n.name_id = m.model_id;");
}

/// Ids of the names in `names`: each name's hash, so that parts of the
/// database written apart agree on them without asking each other; 31 bits,
/// which SQLite stores in 4 bytes (every run repeats them in tens of rows),
/// and two names alike are refused rather than confused (merge_parts checks
/// across parts: one in a million sweeps of 300 names).
class NameIds {
 public:
  explicit NameIds(Database& db) : insert_(db, "INSERT OR IGNORE INTO names VALUES (?, ?);") {}
  int64_t of(const std::string& name) {
    const auto it = ids_.find(name);
    if (it != ids_.end()) return it->second;
    const auto id = static_cast<int64_t>(des::mix64(des::fnv1a64(name)) & 0x7fffffff);
    for (const auto& [other, other_id] : ids_)
      if (other_id == id) throw std::runtime_error("results.sqlite: names \"" + name + "\" and \"" + other + "\" hash alike");
    ids_.emplace(name, id);
    insert_.integer(id).text(name).run();
    return id;
  }

 private:
  Insert insert_;
  std::unordered_map<std::string, int64_t> ids_;
};

/// The prepared inserts of every table a run has rows in.
struct RunInserts {
  explicit RunInserts(Database& db, size_t axes)
      : run(db, "INSERT INTO runs VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?" + repeat(", ?", axes) + ");"),
        figure(db, "INSERT INTO figure_values VALUES (?, ?, ?);"),
        distribution(db, "INSERT INTO distribution_values VALUES (?, ?" + repeat(", ?", kDistributionStats.size()) + ");"),
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

void insert_row(RunInserts& in, int64_t index, const RunRow& r) {
  // A count bound as a real reads back as the integer: the columns' affinity converts it exactly.
  in.run.text(r.run_id).integer(index).integer(static_cast<int64_t>(r.point));
  in.run.integer(static_cast<int64_t>(r.seed)).integer(static_cast<int64_t>(r.replication));
  in.run.optional_real(r.events).optional_real(r.wall_s).optional_real(r.peak_rss_mb);
  if (r.fingerprint) in.run.text(*r.fingerprint);
  else in.run.null();
  for (const auto& v : r.values) in.run.value(v);
  in.run.run();
  for (const auto& f : r.scalars) in.figure.integer(index).integer(in.names.of(f.name)).real(f.value).run();
  for (const auto& d : r.distributions) {
    const int64_t name_id = in.names.of(d.name);
    in.distribution.integer(index).integer(name_id);
    for (const auto& stat : d.stats) in.distribution.optional_real(stat);
    in.distribution.run();
    for (const auto& [stat, v] : d.extra) in.extra.integer(index).integer(name_id).integer(in.names.of(stat)).real(v).run();
  }
  for (const auto& m : r.models)
    in.model.integer(index).integer(in.names.of(m.name)).optional_real(m.events).optional_real(m.wall_s).run();
}

}  // namespace

// The tables a run has rows in, in the order they are merged.
constexpr const char* kRunTables[] = {"runs", "figure_values", "distribution_values", "distribution_extras",
                                      "model_values"};

/// A database of the tables alone (a part, or the whole before its views).
struct Tables {
  Tables(const fs::path& file, const std::vector<std::string>& axis_pointers, bool views) : db(file) {
    // Private until renamed (or removed), so no journal is needed for atomicity;
    // a cache of 64 MB keeps a large sweep's pages in memory until the end.
    db.exec("PRAGMA journal_mode=OFF; PRAGMA synchronous=OFF; PRAGMA cache_size=-65536; BEGIN;");
    create_tables(db, axis_pointers, views);
    inserts = std::make_unique<RunInserts>(db, axis_pointers.size());
  }
  Database db;
  std::unique_ptr<RunInserts> inserts;  // finalized before the database closes
};

/// The database being written, private to its writer until it is renamed
/// into place, and its parts: one per thread that adds runs, each a
/// database of its own beside it, merged into it in order.
struct ResultsDbWriter::Open {
  Open(const fs::path& file, const std::vector<std::string>& axis_pointers, unsigned part_count,
       const std::function<fs::path(unsigned)>& part_file)
      : whole(file, axis_pointers, true) {
    {
      Insert axis(whole.db, "INSERT INTO axes VALUES (?, ?);");
      for (size_t a = 0; a < axis_pointers.size(); ++a) axis.integer(static_cast<int64_t>(a)).text(axis_pointers[a]).run();
    }
    for (unsigned k = 0; k < part_count; ++k) {
      part_files.push_back(part_file(k));
      parts.push_back(std::make_unique<Tables>(part_files.back(), axis_pointers, false));
      parts.back()->db.exec("COMMIT;");
    }
  }
  Tables whole;
  std::vector<fs::path> part_files;
  std::vector<std::unique_ptr<Tables>> parts;
};

ResultsDbWriter::ResultsDbWriter(fs::path file, const std::vector<std::string>& axis_pointers, unsigned parts)
    : file_(std::move(file)), temp_(file_.string() + ".tmp." + std::to_string(::getpid())) {
  remove_files();
  try {
    open_ = std::make_unique<Open>(temp_, axis_pointers, parts, [this](unsigned k) { return part_file(k); });
  } catch (...) {
    open_.reset();
    remove_files();
    throw;
  }
}

fs::path ResultsDbWriter::part_file(unsigned k) const {
  // A temporary name (results.*.tmp.<pid>): what a killed writer leaves is cleared with the others.
  return file_.string() + ".part" + std::to_string(k) + ".tmp." + std::to_string(::getpid());
}

void ResultsDbWriter::remove_files() {
  std::error_code ignored;
  fs::remove(temp_, ignored);
  for (unsigned k = 0;; ++k)
    if (!fs::remove(part_file(k), ignored)) break;
}

ResultsDbWriter::~ResultsDbWriter() {
  if (!open_) return;
  open_.reset();
  remove_files();
}

void ResultsDbWriter::add(const RunRow& row, int64_t position) {
  insert_row(*open_->whole.inserts, position, row);
}

void ResultsDbWriter::begin_part(unsigned part) { open_->parts.at(part)->db.exec("BEGIN;"); }

void ResultsDbWriter::add_to_part(unsigned part, const RunRow& row, int64_t position) {
  insert_row(*open_->parts.at(part)->inserts, position, row);
}

void ResultsDbWriter::end_part(unsigned part) { open_->parts.at(part)->db.exec("COMMIT;"); }

void ResultsDbWriter::merge_parts() {
  Database& db = open_->whole.db;
  // One part attached at a time (SQLite attaches ten at most), outside a
  // transaction; emptied for the next chunk and committed before it is
  // detached, so that its own connection may write it again.
  db.exec("COMMIT;");
  for (const auto& file : open_->part_files) {
    db.exec("ATTACH DATABASE '" + file.string() + "' AS part; BEGIN;");
    {
      Statement clash(db, "SELECT p.name, m.name FROM part.names p JOIN names m ON m.name_id = p.name_id AND "
                          "m.name <> p.name LIMIT 1;");
      if (clash.step())
        db.fail("names \"" + clash.text(0) + "\" and \"" + clash.text(1) + "\" hash alike; rename a figure");
    }
    std::string sql = "INSERT OR IGNORE INTO names SELECT * FROM part.names;";
    for (const char* table : kRunTables) sql += std::string("INSERT INTO ") + table + " SELECT * FROM part." + table + ";";
    sql += "DELETE FROM part.names;";
    for (const char* table : kRunTables) sql += std::string("DELETE FROM part.") + table + ";";
    db.exec(sql + "COMMIT; DETACH DATABASE part;");
  }
  db.exec("BEGIN;");
}

void ResultsDbWriter::commit() {
  Database& db = open_->whole.db;
  open_->whole.inserts.reset();
  db.exec("COMMIT;");
  open_->parts.clear();
  for (const auto& file : open_->part_files) fs::remove(file);
  open_.reset();
  fs::rename(temp_, file_);
}

void write_results_db(const fs::path& file, const std::vector<std::string>& axis_pointers,
                      const std::vector<RunRow>& rows) {
  ResultsDbWriter db(file, axis_pointers);
  for (size_t i = 0; i < rows.size(); ++i) db.add(rows[i], static_cast<int64_t>(i));
  db.commit();
}

}  // namespace latsim::sweep
