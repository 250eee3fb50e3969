// Test helper: damages the global heap of an HDF5 file in its raw bytes.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

namespace evas::test_hdf5 {

// Overwrites the size of the first object of the file's first global-heap
// collection (signature "GCOL") with `size`. Layout (HDF5 File Format
// Specification 2.0, section III.E): the collection header is 16 bytes
// (signature 4, version 1, reserved 3, collection size 8); an object is index
// 2 bytes, reference count 2, reserved 4, size 8, then its data. The
// variable-length strings of evas's body and results files live there.
inline void corrupt_first_heap_object_size(const std::string& path, std::uint64_t size) {
  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::size_t col = bytes.find("GCOL");
  ASSERT_NE(col, std::string::npos) << "no global heap in " << path;
  const std::size_t object = col + 16;
  std::uint16_t index = 0;
  std::memcpy(&index, bytes.data() + object, 2);
  ASSERT_EQ(index, 1) << "the first heap object of " << path << " is not object 1";
  std::memcpy(&bytes[object + 8], &size, 8);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace evas::test_hdf5
