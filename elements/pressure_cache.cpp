// Pressure tables read once per process (PressureTable::read_cached in
// gas_pressure.h): a sweep's every point and run reads the same few files.
#include <deque>
#include <mutex>

#include "elements/gas_pressure.h"
#include "model/file_state.h"

namespace evas {

namespace {

struct TableEntry {
  FileState file;
  double max_gap_deg = 0.0;
  std::shared_ptr<const PressureTable> table;
};

constexpr std::size_t kTables = 64;  // tables kept (the oldest go first)

std::mutex lock;
std::deque<TableEntry> tables;

}  // namespace

std::shared_ptr<const PressureTable> PressureTable::read_cached(const std::string& path,
                                                                double max_gap_deg) {
  FileState f;
  if (!file_state(path, f))  // read() says what is wrong with it
    return std::make_shared<const PressureTable>(read(path, max_gap_deg));
  {
    std::lock_guard<std::mutex> g(lock);
    for (const TableEntry& e : tables)
      if (e.file == f && e.max_gap_deg == max_gap_deg) return e.table;
  }
  auto table = std::make_shared<const PressureTable>(read(path, max_gap_deg));
  if (!file_unchanged(f)) return table;  // replaced while read: not kept
  std::lock_guard<std::mutex> g(lock);
  tables.push_back({f, max_gap_deg, table});
  if (tables.size() > kTables) tables.pop_front();
  return table;
}

}  // namespace evas
