#include "server/document/bulk_release.h"

#include <malloc.h>
#include <boost/asio/post.hpp>

namespace tessera::server {

void releaseOnBulk(const boost::asio::any_io_executor& bulk, std::shared_ptr<void> held) {
  boost::asio::post(bulk, [held = std::move(held)]() mutable {
    held.reset();
    ::malloc_trim(0);
  });
}

void trimHeapOnBulk(const boost::asio::any_io_executor& bulk) {
  boost::asio::post(bulk, [] { ::malloc_trim(0); });
}

}  // namespace tessera::server
