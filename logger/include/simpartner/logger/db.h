// The connection to the MariaDB (or MySQL) server through MySQL Connector/C++
// 1.1 (the legacy JDBC-like API of Debian's libmysqlcppconn-dev). Where the
// server is comes from the parameters (dbserver, dbname) and a client option
// file ([client] user, password, socket or host, port): the password stays
// in that file (mode 0600) and is read by the client library only.
#pragma once

#include <cppconn/resultset.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/parameters.h"

namespace sql {
class Connection;
class Statement;
}  // namespace sql

namespace simpartner::logger {

struct DbTarget {
  std::string option_file;  // client option file with user and password
  std::string socket;       // unix socket path, or empty for TCP
  std::string host;
  int port = 3306;
  std::string database;

  // "unix:///path/mysqld.sock" or "tcp://host:port": what messages name.
  std::string Server() const;
};

// Default client option files of the private server simpartner-mariadb
// (scripts/mariadb) starts: names in its directory, which
// PrivateServerDirectories() (simpartner/data_paths.h) finds.
inline constexpr const char* kPrivateLoggerOptions = "logger.cnf";
inline constexpr const char* kPrivateReaderOptions = "reader.cnf";
inline constexpr const char* kPrivateAdminOptions = "admin.cnf";

// dbserver (host[:port] or a socket path; empty = the option file's socket
// or host), dbname and the option file (`option_file`, or when dbserver is
// empty `default_option_file`: a kPrivate*Options name looked for in the
// private server's directories, or an absolute path). Throws ConfigError naming
// the key or file. Warnings (e.g. an option file others can read) go to
// *warnings.
DbTarget ResolveDbTarget(const Parameters& params, const std::string& option_file,
                         const std::string& default_option_file,
                         std::vector<std::string>* warnings);

// What kind of failure, which decides the message and the retry.
enum class DbErrorKind {
  kUnreachable,  // no connection, or it broke: reconnect and retry
  kRefused,      // the server answers but will not take the writes (read-only, rights, disk full)
  kRetry,        // deadlock or lock wait: retry at once
  kOther,        // anything else (a statement the server does not accept)
};

// A failed database operation, wrapping the Connector/C++ exception with the
// server, the statement (summarised, with its table) and the server's
// error code.
class DbError : public Error {
 public:
  DbError(DbErrorKind kind, std::string server, std::string statement, std::string cause,
          int code, std::string sql_state);
  DbErrorKind kind() const { return kind_; }
  const std::string& server() const { return server_; }
  const std::string& statement() const { return statement_; }
  const std::string& cause() const { return cause_; }
  int code() const { return code_; }
  // what() without the server: "statement: cause (error N, SQLSTATE S)".
  const std::string& detail() const { return detail_; }

 private:
  DbErrorKind kind_;
  std::string server_;
  std::string statement_;
  std::string cause_;
  int code_;
  std::string detail_;
};

DbErrorKind ClassifyServerError(int code);

class DbConnection {
 public:
  // Connects (no database selected yet). local_infile enables LOAD DATA
  // LOCAL. Throws DbError.
  static std::unique_ptr<DbConnection> Open(const DbTarget& target, bool local_infile);
  ~DbConnection();

  // `what` names the statement in errors, e.g. "INSERT INTO Pose (800 rows)".
  void Execute(const std::string& sql, const std::string& what);
  std::unique_ptr<sql::ResultSet> Query(const std::string& sql, const std::string& what);
  // Streams the rows instead of buffering the whole result (exports).
  std::unique_ptr<sql::ResultSet> QueryStreaming(const std::string& sql, const std::string& what);
  // The rows of a server-side prepared statement: the binary protocol,
  // where a DOUBLE comes as its 8 bytes. In the text protocol the server
  // turns every DOUBLE into its shortest text, about 0.7 us each, which is
  // nearly all the time of a bulk read of the per-step tables. The client
  // library stores the whole result (Connector/C++ 1.1 cannot stream a
  // prepared statement's rows): read big results in chunks.
  std::unique_ptr<sql::ResultSet> QueryBinary(const std::string& sql, const std::string& what);
  // First column of the first row as an integer; `fallback` when no row or NULL.
  int64_t QueryInt(const std::string& sql, const std::string& what, int64_t fallback);
  void Begin();
  void Commit();
  void Rollback() noexcept;
  // Selects (creating it if allowed and missing) the database.
  void UseDatabase(bool create);

  const DbTarget& target() const { return target_; }
  // Connector/C++ calls for this thread (getters on result sets) wrapped
  // with the server's name; rethrows sql::SQLException as DbError.
  [[noreturn]] void Rethrow(const std::string& what) const;

 private:
  DbConnection(DbTarget target, std::unique_ptr<sql::Connection> connection);
  DbTarget target_;
  std::unique_ptr<sql::Connection> connection_;
  std::unique_ptr<sql::Statement> statement_;
  std::vector<std::unique_ptr<sql::Statement>> streaming_statements_;
};

// Releases the client library's per-thread state; call at the end of every
// thread that used a DbConnection.
void DbThreadEnd();

// A name for use inside backquotes (rejects a backquote or NUL).
std::string QuoteIdentifier(const std::string& name);

}  // namespace simpartner::logger
