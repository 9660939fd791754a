// Worker pool, timeouts and listen backlog of the viewer's server.
#include "app/viewer/connection_limits.h"

#include <sys/socket.h>

#include <memory>

#include <httplib.h>

#include "app/viewer/worker_pool.h"

namespace glint {

void applyConnectionLimits(httplib::Server& http, const ConnectionLimits& limits) {
  http.new_task_queue = [limits] { return new WorkerPool(limits.workers, limits.maxQueued); };
  http.set_read_timeout(limits.readWriteSeconds, 0);
  http.set_write_timeout(limits.readWriteSeconds, 0);
  http.set_keep_alive_timeout(limits.keepAliveSeconds);
}

int bindWithBacklog(httplib::Server& http, const std::string& host, int port, int backlog) {
  // SO_REUSEADDR only: the library's default adds SO_REUSEPORT, which would let another
  // process of the user bind the same port and receive a share of the viewer's connections.
  auto listenSocket = std::make_shared<socket_t>(-1);
  http.set_socket_options([listenSocket](socket_t sock) {
    int yes = 1;
    ::setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof(yes));
    *listenSocket = sock;  // the last socket tried is the bound one when binding succeeds
  });
  int bound = port == 0 ? http.bind_to_any_port(host) : (http.bind_to_port(host, port) ? port : -1);
  // Listening again on a listening socket only resizes its backlog (Linux, BSD).
  if (bound > 0) ::listen(*listenSocket, backlog);
  return bound;
}

}  // namespace glint
