#include "simpartner/logger/db.h"

#include <mysql_driver.h>
#include <cppconn/connection.h>
#include <cppconn/driver.h>
#include <cppconn/exception.h>
#include <cppconn/statement.h>
#include <cppconn/prepared_statement.h>
#include <sys/stat.h>

#include "simpartner/bounded_file.h"
#include "simpartner/data_paths.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/text.h"

#include <cctype>
#include <sstream>

namespace simpartner::logger {
namespace {

std::string Unquote(const std::string& s) {
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front())
    return s.substr(1, s.size() - 2);
  return s;
}

// Where-to-connect keys of the [client] group (never the password).
struct ClientOptions {
  std::string socket, host, port, database;
  bool has_user = false;
};

ClientOptions ReadClientOptions(const std::string& path, DiagnosticList* diagnostics) {
  ClientOptions options;
  std::string text;
  try {
    text = ReadBoundedFile(path, kMaxSettingsFileBytes, "database option files");
  } catch (const FileReadError& e) {
    diagnostics->Add(path, 0, "",
                     e.cannot_open()
                         ? std::string("cannot open the database option file: ") + e.what()
                         : e.what());
    return options;
  }
  std::istringstream in(text);
  std::string line;
  std::string group;
  while (std::getline(in, line)) {
    line = Trim(line);
    if (line.empty() || line[0] == '#' || line[0] == ';' || line[0] == '!') continue;
    if (line.front() == '[' && line.back() == ']') {
      group = Trim(line.substr(1, line.size() - 2));
      continue;
    }
    if (group != "client" && group != "client-mariadb") continue;
    const size_t eq = line.find('=');
    std::string key = Trim(line.substr(0, eq));
    for (char& c : key) c = c == '-' ? '_' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const std::string value = eq == std::string::npos ? "" : Unquote(Trim(line.substr(eq + 1)));
    if (key == "socket") options.socket = value;
    else if (key == "host") options.host = value;
    else if (key == "port") options.port = value;
    else if (key == "database") options.database = value;
    else if (key == "user") options.has_user = true;
  }
  return options;
}

int ParsePort(const std::string& text, const std::string& where, const std::string& key,
              DiagnosticList* diagnostics) {
  char* end = nullptr;
  const long port = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || port < 1 || port > 65535) {
    diagnostics->Add(where, 0, key, "port '" + text + "' is not a number from 1 to 65535");
    return 3306;
  }
  return static_cast<int>(port);
}

bool IsSocketPath(const std::string& s) { return !s.empty() && (s[0] == '/' || s[0] == '.'); }

}  // namespace

std::string DbTarget::Server() const {
  if (!socket.empty()) return "unix://" + socket;
  return "tcp://" + host + ":" + std::to_string(port);
}

DbTarget ResolveDbTarget(const Parameters& params, const std::string& option_file,
                         const std::string& default_option_file,
                         std::vector<std::string>* warnings) {
  DiagnosticList diagnostics;
  DbTarget target;
  target.database = params.dbname;
  if (target.database.empty())
    diagnostics.Add("parameters", 0, "dbname", "is empty (a database name is needed)");
  for (const char c : target.database) {
    if (c == '`' || c == '\0' || c == '/' || c == '\\' || c == '.') {
      diagnostics.Add("parameters", 0, "dbname",
                      "value '" + target.database + "' has a character a database name cannot have");
      break;
    }
  }
  target.option_file = option_file;
  if (target.option_file.empty()) {
    if (!params.dbserver.empty()) {
      diagnostics.Add("parameters", 0, "dbserver",
                      "server '" + params.dbserver +
                          "' needs credentials: pass --db-options FILE, a MariaDB option file "
                          "with [client] user= and password= (mode 0600)");
      throw ConfigError(diagnostics);
    }
    // The private server's file (common/.../data_paths.h says where it is
    // looked for, as simpartner-mariadb puts it).
    const std::vector<DataCandidate> tried = PrivateServerFileCandidates(default_option_file);
    for (const DataCandidate& c : tried) {
      struct stat file {};
      if (::stat(c.path.c_str(), &file) == 0 && !S_ISDIR(file.st_mode)) {
        target.option_file = c.path;
        break;
      }
    }
    if (target.option_file.empty()) {
      diagnostics.Add(default_option_file, 0, "dbserver",
                      "dbserver is empty, so the private server's option file is used, but it "
                      "is in none of these places:\n" +
                          FormatCandidates(tried) +
                          "start the server with simpartner-mariadb start (scripts/mariadb start "
                          "in a source tree; scripts/run starts it in the repository's state/), "
                          "or set dbserver and --db-options");
      throw ConfigError(diagnostics);
    }
  }
  const ClientOptions options = ReadClientOptions(target.option_file, &diagnostics);
  struct stat st {};
  if (::stat(target.option_file.c_str(), &st) == 0 && (st.st_mode & 077) != 0 && warnings) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(st.st_mode & 07777));
    warnings->push_back(target.option_file + ": readable by others (mode " + mode +
                        "); it holds a password: chmod 600 it");
  }
  if (diagnostics.empty() && !options.has_user)
    diagnostics.Add(target.option_file, 0, "user", "no user= in its [client] group");

  if (!params.dbserver.empty()) {
    if (IsSocketPath(params.dbserver)) {
      target.socket = params.dbserver;
    } else {
      const size_t colon = params.dbserver.rfind(':');
      target.host = params.dbserver.substr(0, colon);
      if (colon != std::string::npos)
        target.port = ParsePort(params.dbserver.substr(colon + 1), "parameters", "dbserver",
                                &diagnostics);
      if (target.host.empty())
        diagnostics.Add("parameters", 0, "dbserver",
                        "value '" + params.dbserver + "' has no host name");
    }
  } else if (!options.socket.empty()) {
    target.socket = options.socket;
  } else if (!options.host.empty() && options.host != "localhost") {
    target.host = options.host;
    if (!options.port.empty()) target.port = ParsePort(options.port, target.option_file, "port", &diagnostics);
  } else if (diagnostics.empty()) {
    diagnostics.Add(target.option_file, 0, "socket",
                    "names neither socket= nor host=, and dbserver is empty: where is the server?");
  }
  if (!diagnostics.empty()) throw ConfigError(diagnostics);
  return target;
}

DbErrorKind ClassifyServerError(int code) {
  switch (code) {
    case 2002: case 2003: case 2005: case 2006: case 2013: case 2055: case 2026:
    case 1040: case 1053: case 1129: case 1927: case 1152: case 1184:
      return DbErrorKind::kUnreachable;
    case 1290:  // --read-only and the like
    case 1036: case 1792:  // read-only table / transaction
    case 1044: case 1045: case 1142: case 1143: case 1227:  // rights
    case 1021: case 1114: case 1030: case 3: case 1206:  // disk or table full, engine errors
      return DbErrorKind::kRefused;
    case 1205: case 1213:
      return DbErrorKind::kRetry;
    default:
      return DbErrorKind::kOther;
  }
}

DbError::DbError(DbErrorKind kind, std::string server, std::string statement, std::string cause,
                 int code, std::string sql_state)
    : Error(server + ": " + statement + ": " + cause +
            (code != 0 ? " (error " + std::to_string(code) + ", SQLSTATE " + sql_state + ")" : "")),
      kind_(kind),
      server_(std::move(server)),
      statement_(std::move(statement)),
      cause_(std::move(cause)),
      code_(code),
      detail_(std::string(what()).substr(server_.size() + 2)) {}

DbConnection::DbConnection(DbTarget target, std::unique_ptr<sql::Connection> connection)
    : target_(std::move(target)), connection_(std::move(connection)) {}

DbConnection::~DbConnection() {
  statement_.reset();
  try {
    if (connection_) connection_->close();
  } catch (const sql::SQLException&) {
    // A connection that is already broken has nothing to close.
  }
}

void DbConnection::Rethrow(const std::string& what) const {
  try {
    throw;
  } catch (const sql::SQLException& e) {
    std::string cause = e.what();
    if (cause.empty()) cause = "(the client library gave no message)";
    throw DbError(ClassifyServerError(e.getErrorCode()), target_.Server(), what, cause,
                  e.getErrorCode(), e.getSQLState());
  }
}

std::unique_ptr<DbConnection> DbConnection::Open(const DbTarget& target, bool local_infile) {
  sql::ConnectOptionsMap options;
  options["hostName"] = sql::SQLString(target.socket.empty()
                                           ? "tcp://" + target.host + ":" + std::to_string(target.port)
                                           : "unix://" + target.socket);
  // User and password come from the file, read by the client library.
  options["readDefaultFile"] = sql::SQLString(target.option_file);
  options["readDefaultGroup"] = sql::SQLString("client");
  options["OPT_CONNECT_TIMEOUT"] = 5;
  // A server that stops answering (stopped, not closed) must not hang the
  // writer for ever.
  options["OPT_READ_TIMEOUT"] = 60;
  options["OPT_WRITE_TIMEOUT"] = 60;
  options["OPT_RECONNECT"] = false;
  options["OPT_LOCAL_INFILE"] = local_infile ? 1 : 0;
  options["OPT_CHARSET_NAME"] = sql::SQLString("utf8mb4");
  std::unique_ptr<sql::Connection> connection;
  try {
    connection.reset(sql::mysql::get_mysql_driver_instance()->connect(options));
  } catch (const sql::SQLException& e) {
    throw DbError(ClassifyServerError(e.getErrorCode()), target.Server(),
                  "connect (options from " + target.option_file + ")", e.what(), e.getErrorCode(),
                  e.getSQLState());
  }
  std::unique_ptr<DbConnection> db(new DbConnection(target, std::move(connection)));
  try {
    db->statement_.reset(db->connection_->createStatement());
  } catch (const sql::SQLException&) {
    db->Rethrow("create statement");
  }
  // Strict: a value the column cannot hold is an error, never a silent
  // truncation. Backslash escapes on (sql_text.h relies on them). UTC.
  db->Execute("SET SESSION sql_mode = 'STRICT_ALL_TABLES,NO_ZERO_DATE,NO_ENGINE_SUBSTITUTION', "
              "time_zone = '+00:00'",
              "SET SESSION sql_mode, time_zone");
  return db;
}

void DbConnection::Execute(const std::string& sql, const std::string& what) {
  try {
    statement_->execute(sql);
  } catch (const sql::SQLException&) {
    Rethrow(what);
  }
}

std::unique_ptr<sql::ResultSet> DbConnection::Query(const std::string& sql, const std::string& what) {
  try {
    return std::unique_ptr<sql::ResultSet>(statement_->executeQuery(sql));
  } catch (const sql::SQLException&) {
    Rethrow(what);
  }
}

std::unique_ptr<sql::ResultSet> DbConnection::QueryStreaming(const std::string& sql,
                                                             const std::string& what) {
  try {
    std::unique_ptr<sql::Statement> statement(connection_->createStatement());
    statement->setResultSetType(sql::ResultSet::TYPE_FORWARD_ONLY);
    std::unique_ptr<sql::ResultSet> rows(statement->executeQuery(sql));
    // The result set keeps a pointer to its statement: keep it alive.
    streaming_statements_.push_back(std::move(statement));
    return rows;
  } catch (const sql::SQLException&) {
    Rethrow(what);
  }
}

std::unique_ptr<sql::ResultSet> DbConnection::QueryBinary(const std::string& sql,
                                                          const std::string& what) {
  try {
    std::unique_ptr<sql::PreparedStatement> statement(connection_->prepareStatement(sql));
    std::unique_ptr<sql::ResultSet> rows(statement->executeQuery());
    // The result set keeps a pointer to its statement: keep it alive.
    streaming_statements_.push_back(std::move(statement));
    return rows;
  } catch (const sql::SQLException&) {
    Rethrow(what);
  }
}

int64_t DbConnection::QueryInt(const std::string& sql, const std::string& what, int64_t fallback) {
  try {
    std::unique_ptr<sql::ResultSet> rows(statement_->executeQuery(sql));
    if (!rows->next() || rows->isNull(1)) return fallback;
    return rows->getInt64(1);
  } catch (const sql::SQLException&) {
    Rethrow(what);
  }
}

// Transactions are plain statements, not Connector/C++'s setAutoCommit(),
// commit() and rollback(): Connector/C++ 1.1.12 (Debian 12) ignores the
// result of mysql_commit() and mysql_autocommit(), so a COMMIT sent to a
// server that had just shut down "succeeded" and the batch was dropped from
// the queue although the server never committed it (seen: 60 steps lost in
// the 30 s outage test). A statement's failure always throws.
void DbConnection::Begin() { Execute("START TRANSACTION", "begin transaction"); }

void DbConnection::Commit() { Execute("COMMIT", "commit"); }

void DbConnection::Rollback() noexcept {
  try {
    statement_->execute("ROLLBACK");
  } catch (const sql::SQLException&) {
    // The connection is broken; the server rolls the transaction back.
  }
}

void DbConnection::UseDatabase(bool create) {
  const std::string name = QuoteIdentifier(target_.database);
  if (create) {
    const int64_t exists = QueryInt(
        "SELECT COUNT(*) FROM information_schema.SCHEMATA WHERE SCHEMA_NAME = " +
            Quoted(target_.database),
        "look up database " + target_.database, 0);
    if (exists == 0)
      Execute("CREATE DATABASE " + name + " CHARACTER SET utf8mb4",
              "CREATE DATABASE " + target_.database);
  }
  Execute("USE " + name, "USE " + target_.database);
}

void DbThreadEnd() { sql::mysql::get_mysql_driver_instance()->threadEnd(); }

std::string QuoteIdentifier(const std::string& name) {
  for (const char c : name)
    if (c == '`' || c == '\0') throw Error("database name '" + name + "' has a backquote or NUL");
  return "`" + name + "`";
}

}  // namespace simpartner::logger
