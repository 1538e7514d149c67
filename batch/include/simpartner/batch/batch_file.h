// A batch file (batch/dtd/batch.dtd): the world, the fixed parameters, the
// controller, the seeds, the sweep and the figures of a batch of runs.
// Read and checked whole before anything starts: an unknown element or
// attribute (the DTD), a world that is not found, a parameter key nobody
// knows or a value out of its range, a controller variable the command
// never names are refused with the batch file's line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner::batch {

// One swept quantity: a sim parameter (key) or a controller variable (name).
struct Vary {
  int line = 0;
  bool is_parameter = false;
  std::string name;                  // the key, or the variable's name
  std::vector<std::string> values;
};

enum class Quantity { kX, kY, kZ, kPathLength, kFinalSpeed, kPeakContactForce };

struct Figure {
  int line = 0;
  std::string name;
  std::string body;  // as the model names it
  Quantity quantity = Quantity::kX;
};

struct BatchFile {
  std::string file;            // as read
  std::string name;
  std::string world;           // the found path
  std::string robot;           // "" = the world's own
  std::vector<std::pair<std::string, std::string>> parameters;  // key, value
  double duration = 0;         // [s] of sim time
  std::string controller;      // command line with {placeholders}; or
  std::string sequence;        // the found path of a sequence file
  std::vector<long long> seeds;  // at least one (0 when none is given)
  bool grid = true;
  std::vector<Vary> sweep;
  std::vector<Figure> figures;
};

// The most runs a batch may have: each is a folder, a result file, a row
// of the summary and, on Slurm, a task of one job array (whose size a
// cluster's MaxArraySize bounds, 1,001 by default). Larger studies are
// several batches.
inline constexpr int kMaxRuns = 10000;

struct BatchParseResult {
  std::optional<BatchFile> batch;  // set only when there were no errors
  DiagnosticList diagnostics;
};

// Parses and checks text (file_name for messages and for finding the world
// and sequence next to it).
BatchParseResult ParseBatchFile(const std::string& text, const std::string& file_name);
// Reads the file (a regular file, bounded) and parses it; a file that
// cannot be read is a diagnostic at line 0.
BatchParseResult LoadBatchFile(const std::string& path);

const char* QuantityName(Quantity quantity);

}  // namespace simpartner::batch
