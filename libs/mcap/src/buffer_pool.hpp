// Buffers for chunks, handed back when the last message pointing into them has been visited and
// handed out again for the next chunk. Fresh memory costs a page fault per 4 KiB on first touch,
// which on a virtual machine costs more than decompressing into it; reused buffers are already
// mapped.
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include "byte_io.hpp"

namespace uampc::mcap::detail {

class BufferPool {
 public:
  // At most `keep` idle buffers are kept; more are freed.
  explicit BufferPool(std::size_t keep = 4);

  // An empty buffer (its capacity possibly from an earlier chunk), back in the pool when the last
  // shared_ptr to it goes; a buffer outliving the pool is simply freed.
  std::shared_ptr<Buffer> get();

 private:
  struct Idle {
    std::size_t keep;
    std::vector<std::unique_ptr<Buffer>> buffers;
  };
  std::shared_ptr<Idle> idle_;
};

}  // namespace uampc::mcap::detail
