// image/image_io_detail.h — private to image_io.cpp and its tests: the seam through which tests
// make a file write fail (a full disk, an I/O error) without needing a full disk.
#pragma once

#include <cstddef>

namespace footprint::detail {

// The write(2) that save_image, save_images and write_file_atomically call for every chunk of a
// file: returns the number of bytes written, or −1 with errno set.
using WriteCall = long (*)(int fd, const void* data, std::size_t size);

// Makes image_io write through `call` (nullptr: the system's write()) and returns the previous
// call. Not thread-safe: tests set it around the saves they check.
WriteCall replace_write_call_for_testing(WriteCall call);

}  // namespace footprint::detail
