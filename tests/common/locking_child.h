// A child process that takes a lock and holds it until the test lets it go, for tests of a
// second writer. The child runs only `take` and system calls after fork: a test process may
// have other threads (a viewer's) holding malloc's lock at the fork.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

namespace glint::test {

struct LockingChild {
  pid_t pid = -1;
  int release = -1;  // the parent's end of the pipe the child waits on
};

// Forks a child that calls take() (which must leave the lock held, e.g. an fd left open),
// tells the parent, and waits until finish(); returns once the child holds the lock.
inline LockingChild holdLockInChild(const std::function<bool()>& take) {
  int ready[2], release[2];
  EXPECT_EQ(pipe(ready), 0);
  EXPECT_EQ(pipe(release), 0);
  const pid_t pid = fork();
  if (pid == 0) {
    close(ready[0]), close(release[1]);
    if (!take()) _exit(1);
    char c = 1;
    (void)!write(ready[1], &c, 1);
    (void)!read(release[0], &c, 1);  // until the parent closes its end
    _exit(0);
  }
  close(ready[1]), close(release[0]);
  char c = 0;
  EXPECT_EQ(read(ready[0], &c, 1), 1);
  close(ready[0]);
  return {pid, release[1]};
}

// Lets the child go and waits for it.
inline void finish(const LockingChild& child) {
  close(child.release);
  int status = 0;
  waitpid(child.pid, &status, 0);
}

}  // namespace glint::test
