/* A storage that fails, for the tests: LD_PRELOAD this library and the writes of a process to
 * the files whose path contains MPMXDEM_FAIL_PATH fail with errno MPMXDEM_FAIL_ERRNO (default
 * ENOSPC, "No space left on device") once MPMXDEM_FAIL_AFTER bytes (default 0) have been written
 * to such files in all. As a full disk or an exceeded quota does: from then on a write or an
 * allocation that needs new space fails (it reaches past the file's end, or the file is new),
 * while rewriting bytes a file already holds succeeds. With MPMXDEM_FAIL_ALL=1 every write to
 * such files fails from then on, fsync included (a device that fails: EIO). Other files, reads
 * and the MPI library's own shared memory are left alone. One kind of output file at a time
 * (tests/app/storage_faults.sh).
 *
 * Interposed: open, open64, openat, openat64, creat, creat64, fopen, fopen64 (to learn which
 * descriptors are such files), write, pwrite, pwrite64, writev, pwritev, pwritev64,
 * posix_fallocate(64), fallocate (an allocation fails where a write of its size would, and is
 * not counted: mpmxdem allocates only to probe for room), fsync,
 * fdatasync, close. Enough for HDF5's sec2 driver, libstdc++'s file streams (fopen and write)
 * and plain POSIX I/O; C stdio's own buffered writes (fwrite, fprintf) do not go through write()
 * here and are not failed. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/uio.h>
#include <unistd.h>

#define MAX_FD 4096

static char watched[MAX_FD];
static long long written; /* bytes written to watched files by this process */
static int tripped;        /* a write failed: the storage stays full */

static const char* pattern(void) {
  const char* p = getenv("MPMXDEM_FAIL_PATH");
  return p != NULL && p[0] != '\0' ? p : NULL;
}

static long long limit(void) {
  const char* a = getenv("MPMXDEM_FAIL_AFTER");
  return a != NULL ? atoll(a) : 0;
}

static int fail_errno(void) {
  const char* e = getenv("MPMXDEM_FAIL_ERRNO");
  return e != NULL && atoi(e) > 0 ? atoi(e) : ENOSPC;
}

static void note(int fd, const char* path, int writable) {
  const char* p = pattern();
  if (fd < 0 || fd >= MAX_FD) return;
  watched[fd] = (char)(writable && p != NULL && path != NULL && strstr(path, p) != NULL);
}

static int fail_all(void) {
  const char* a = getenv("MPMXDEM_FAIL_ALL");
  return a != NULL && atoi(a) != 0;
}

/* Whether a write of n bytes at offset `at` of fd (-1: the current position) fails (it is counted
 * when it does not, unless `probe`: an allocation that the caller gives back at once). */
static int refuse_probe(int fd, size_t n, long long at, int probe) {
  if (fd < 0 || fd >= MAX_FD || !watched[fd]) return 0;
  if (tripped && !fail_all()) {
    struct stat st;
    if (at < 0) at = (long long)lseek(fd, 0, SEEK_CUR);
    if (at >= 0 && fstat(fd, &st) == 0 && at + (long long)n <= (long long)st.st_size) return 0;
  }
  if (tripped || written + (long long)n > limit()) {
    tripped = 1;
    errno = fail_errno();
    return 1;
  }
  if (!probe) written += (long long)n;
  return 0;
}

static int refuse_at(int fd, size_t n, long long at) { return refuse_probe(fd, n, at, 0); }
static int refuse(int fd, size_t n) { return refuse_at(fd, n, -1); }

#define REAL(ret, name, ...)                                     \
  static ret (*real)(__VA_ARGS__) = NULL;                        \
  if (real == NULL) real = (ret(*)(__VA_ARGS__))dlsym(RTLD_NEXT, name)

static int writable_flags(int flags) { return (flags & (O_WRONLY | O_RDWR)) != 0; }

static mode_t mode_of(int flags, va_list ap) {
  return (flags & (O_CREAT | O_TMPFILE)) != 0 ? (mode_t)va_arg(ap, int) : 0;
}

/* open, open64, openat and openat64: the real call, then note what the descriptor is. */
#define OPEN_LIKE(name, dir_param, dir_arg)                              \
  int name(dir_param const char* path, int flags, ...) {                \
    REAL(int, #name, dir_param const char*, int, ...);                   \
    va_list ap;                                                          \
    va_start(ap, flags);                                                 \
    const mode_t mode = mode_of(flags, ap);                              \
    va_end(ap);                                                          \
    const int fd = real(dir_arg path, flags, mode);                      \
    note(fd, path, writable_flags(flags));                               \
    return fd;                                                           \
  }
#define NO_DIR
#define DIR_PARAM int dir,
#define DIR_ARG dir,
OPEN_LIKE(open, NO_DIR, NO_DIR)
OPEN_LIKE(open64, NO_DIR, NO_DIR)
OPEN_LIKE(openat, DIR_PARAM, DIR_ARG)
OPEN_LIKE(openat64, DIR_PARAM, DIR_ARG)

int creat(const char* path, mode_t mode) { return open(path, O_WRONLY | O_CREAT | O_TRUNC, mode); }

int creat64(const char* path, mode_t mode) {
  return open64(path, O_WRONLY | O_CREAT | O_TRUNC, mode);
}

static int writable_mode(const char* mode) { return strpbrk(mode, "wa+") != NULL; }

FILE* fopen(const char* path, const char* mode) {
  REAL(FILE*, "fopen", const char*, const char*);
  FILE* f = real(path, mode);
  if (f != NULL) note(fileno(f), path, writable_mode(mode));
  return f;
}

FILE* fopen64(const char* path, const char* mode) {
  REAL(FILE*, "fopen64", const char*, const char*);
  FILE* f = real(path, mode);
  if (f != NULL) note(fileno(f), path, writable_mode(mode));
  return f;
}

ssize_t write(int fd, const void* buf, size_t n) {
  REAL(ssize_t, "write", int, const void*, size_t);
  return refuse(fd, n) ? -1 : real(fd, buf, n);
}

ssize_t pwrite(int fd, const void* buf, size_t n, off_t at) {
  REAL(ssize_t, "pwrite", int, const void*, size_t, off_t);
  return refuse_at(fd, n, (long long)at) ? -1 : real(fd, buf, n, at);
}

ssize_t pwrite64(int fd, const void* buf, size_t n, off64_t at) {
  REAL(ssize_t, "pwrite64", int, const void*, size_t, off64_t);
  return refuse_at(fd, n, (long long)at) ? -1 : real(fd, buf, n, at);
}

static size_t total(const struct iovec* v, int n) {
  size_t s = 0;
  for (int i = 0; i < n; ++i) s += v[i].iov_len;
  return s;
}

ssize_t writev(int fd, const struct iovec* v, int n) {
  REAL(ssize_t, "writev", int, const struct iovec*, int);
  return refuse(fd, total(v, n)) ? -1 : real(fd, v, n);
}

ssize_t pwritev(int fd, const struct iovec* v, int n, off_t at) {
  REAL(ssize_t, "pwritev", int, const struct iovec*, int, off_t);
  return refuse_at(fd, total(v, n), (long long)at) ? -1 : real(fd, v, n, at);
}

ssize_t pwritev64(int fd, const struct iovec* v, int n, off64_t at) {
  REAL(ssize_t, "pwritev64", int, const struct iovec*, int, off64_t);
  return refuse_at(fd, total(v, n), (long long)at) ? -1 : real(fd, v, n, at);
}

int posix_fallocate(int fd, off_t at, off_t n) {
  REAL(int, "posix_fallocate", int, off_t, off_t);
  return refuse_probe(fd, (size_t)n, (long long)at, 1) ? errno : real(fd, at, n);
}

int posix_fallocate64(int fd, off64_t at, off64_t n) {
  REAL(int, "posix_fallocate64", int, off64_t, off64_t);
  return refuse_probe(fd, (size_t)n, (long long)at, 1) ? errno : real(fd, at, n);
}

int fallocate(int fd, int mode, off_t at, off_t n) {
  REAL(int, "fallocate", int, int, off_t, off_t);
  return refuse_probe(fd, (size_t)n, (long long)at, 1) ? -1 : real(fd, mode, at, n);
}

static int refuse_sync(int fd) {
  if (fd < 0 || fd >= MAX_FD || !watched[fd] || !tripped || !fail_all()) return 0;
  errno = fail_errno();
  return 1;
}

int fsync(int fd) {
  REAL(int, "fsync", int);
  return refuse_sync(fd) ? -1 : real(fd);
}

int fdatasync(int fd) {
  REAL(int, "fdatasync", int);
  return refuse_sync(fd) ? -1 : real(fd);
}

int close(int fd) {
  REAL(int, "close", int);
  if (fd >= 0 && fd < MAX_FD) watched[fd] = 0;
  return real(fd);
}
