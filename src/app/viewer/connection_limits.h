// The viewer's limits on connections, for cpp-httplib 0.11 (Debian 12): how many are served
// at once, how many wait, how long a client may take to send or read, and a listen backlog
// wide enough for bursts (the library's is 5: connects beyond it wait for SYN retransmits
// after 1, 3, 7 s...).
#pragma once

#include <string>

namespace httplib {
class Server;
}

namespace glint {

struct ConnectionLimits {
  // Connections served at once. Each long-polling page holds one for its keep-alive life
  // (frames wait up to 1 s), so 64 polling clients leave 64 workers for everything else.
  size_t workers = 128;
  size_t maxQueued = 256;  // accepted connections waiting for a worker (worker_pool.h)
  int backlog = 512;       // connections the kernel holds before they are accepted
  // A client that sends or reads nothing for this long loses its connection, and an idle
  // keep-alive connection frees its worker after keepAliveSeconds.
  int readWriteSeconds = 5;
  int keepAliveSeconds = 2;
};

// Installs the worker pool and the timeouts; call before binding.
void applyConnectionLimits(httplib::Server& http, const ConnectionLimits& limits);

// Binds host:port (port 0: any free port) and widens the listen backlog. Returns the port, or -1.
int bindWithBacklog(httplib::Server& http, const std::string& host, int port, int backlog);

}  // namespace glint
