// The query library (target sp_logger_query): what is in the logger's
// database, for people and for spreadsheets, Octave or Python. It holds no
// writer, receiver or spool; simpartner-query and the Python module link it
// alone.
//   simulations.h  the list, a simulation by id/"last"/"running", names
//   export.h       poses, contact forces or joint states step by step, CSV
//   logged_run.h   a run as arrays (Python's read_logged, the plots)
//   plot_query.h   gnuplot plots of a run
//   admin.h        delete, prune, table sizes, page compression
#pragma once

#include "simpartner/logger/admin.h"
#include "simpartner/logger/db.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/logged_run.h"
#include "simpartner/logger/plot_query.h"
#include "simpartner/logger/simulations.h"
