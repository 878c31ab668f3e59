#pragma once
// What the server's registry (server_state.hpp) needs of a live WebSocket session, whichever
// protocol it speaks: a way to wind it down at stop, and the object the publisher holds, whose
// link to the session is cut before the io_context goes (a publisher may outlive the server).

namespace avk::server {

class LiveSession {
 public:
  virtual ~LiveSession() = default;
  // Any thread: close with 1001 (going away).
  virtual void shutdown() = 0;
};

class DetachableSink {
 public:
  virtual ~DetachableSink() = default;
  // After this returns, the sink reaches no session; waits out a delivery in progress.
  virtual void detach() = 0;
};

}  // namespace avk::server
