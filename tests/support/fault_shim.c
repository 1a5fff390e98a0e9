/* A fault injector for tests of the real binaries, loaded with LD_PRELOAD. It stands between the
 * program and the C library's fsync and rename, the two calls a full disk does not make fail:
 *
 *   RECON_FAULT=fsync:N    the N-th fsync or fdatasync of a file (not a folder) of the process
 *                          fails with EIO, undone
 *   RECON_FAULT=dirsync:N  the same for the N-th of a folder (made after a rename into it)
 *   RECON_FAULT=rename:N   the N-th rename, renameat or renameat2 fails with EIO, undone
 *   RECON_FAULT_COUNTS=F   at exit, appends "fsync <calls> dirsync <calls> rename <calls>" to
 *                          the file F, so a test can first count the calls and then fail each
 *   RECON_FAULT_ACTION=A   what happens at that call: fail (the default: EIO), kill-before (the
 *                          process kills itself with SIGKILL instead of making the call) or
 *                          kill-after (the call is made, then SIGKILL): a kill -9 at an exact
 *                          point of a write, where a timed kill lands by chance
 *
 * EIO is what a failing disk or a network file system gives; the program must report it and
 * leave every file it had saved as it was. Everything else passes through untouched. */

#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

enum { kFsync = 0, kDirSync = 1, kRename = 2, kKinds = 3 };
enum { kFail = 0, kKillBefore = 1, kKillAfter = 2 };

static long calls[kKinds];
static int fault_kind = -1;
static long fault_at = 0;
static int fault_action = kFail;

__attribute__((constructor)) static void ReadFaultSetting(void) {
  const char* setting = getenv("RECON_FAULT");
  if (setting == NULL) return;
  const char* colon = strchr(setting, ':');
  const size_t name_length = colon == NULL ? 0 : (size_t)(colon - setting);
  if (name_length == 5 && strncmp(setting, "fsync", 5) == 0) fault_kind = kFsync;
  if (name_length == 7 && strncmp(setting, "dirsync", 7) == 0) fault_kind = kDirSync;
  if (name_length == 6 && strncmp(setting, "rename", 6) == 0) fault_kind = kRename;
  char* end = NULL;
  if (colon != NULL) fault_at = strtol(colon + 1, &end, 10);
  /* A mistyped setting would inject nothing and let a fault test pass for the wrong reason. */
  if (fault_kind < 0 || fault_at < 1 || end == NULL || *end != '\0') {
    fprintf(stderr, "fault_shim: RECON_FAULT='%s' is not fsync:N, dirsync:N or rename:N\n",
            setting);
    _exit(97);
  }
  const char* action = getenv("RECON_FAULT_ACTION");
  if (action == NULL || strcmp(action, "fail") == 0) return;
  if (strcmp(action, "kill-before") == 0) {
    fault_action = kKillBefore;
  } else if (strcmp(action, "kill-after") == 0) {
    fault_action = kKillAfter;
  } else {
    fprintf(stderr, "fault_shim: RECON_FAULT_ACTION='%s' is not fail, kill-before or kill-after\n",
            action);
    _exit(97);
  }
}

__attribute__((destructor)) static void WriteCallCounts(void) {
  const char* path = getenv("RECON_FAULT_COUNTS");
  if (path == NULL) return;
  FILE* out = fopen(path, "a");
  if (out == NULL) return;
  fprintf(out, "fsync %ld dirsync %ld rename %ld\n",
          __atomic_load_n(&calls[kFsync], __ATOMIC_SEQ_CST),
          __atomic_load_n(&calls[kDirSync], __ATOMIC_SEQ_CST),
          __atomic_load_n(&calls[kRename], __ATOMIC_SEQ_CST));
  fclose(out);
}

/* True when this call of `kind` is the one to fail (errno is then EIO). With kill-before the
 * process dies here instead; with kill-after, `*kill_after` is set for the caller, which makes
 * the call and then dies. */
static int ShouldFail(int kind, int* kill_after) {
  const long call = __atomic_add_fetch(&calls[kind], 1, __ATOMIC_SEQ_CST);
  if (kind != fault_kind || call != fault_at) return 0;
  if (fault_action == kKillBefore) raise(SIGKILL);
  if (fault_action == kKillAfter) {
    *kill_after = 1;
    return 0;
  }
  errno = EIO;
  return 1;
}

/* Passes on the result of a call made, first dying if this was the call to kill after. */
static int Then(int result, int kill_after) {
  if (kill_after) raise(SIGKILL);
  return result;
}

static void* Next(const char* name) { return dlsym(RTLD_NEXT, name); }

/* kDirSync for a folder's descriptor, else kFsync. */
static int SyncKind(int fd) {
  struct stat st;
  return fstat(fd, &st) == 0 && S_ISDIR(st.st_mode) ? kDirSync : kFsync;
}

int fsync(int fd) {
  int kill_after = 0;
  if (ShouldFail(SyncKind(fd), &kill_after)) return -1;
  return Then(((int (*)(int))Next("fsync"))(fd), kill_after);
}

int fdatasync(int fd) {
  int kill_after = 0;
  if (ShouldFail(SyncKind(fd), &kill_after)) return -1;
  return Then(((int (*)(int))Next("fdatasync"))(fd), kill_after);
}

int rename(const char* from, const char* to) {
  int kill_after = 0;
  if (ShouldFail(kRename, &kill_after)) return -1;
  return Then(((int (*)(const char*, const char*))Next("rename"))(from, to), kill_after);
}

int renameat(int from_dir, const char* from, int to_dir, const char* to) {
  int kill_after = 0;
  if (ShouldFail(kRename, &kill_after)) return -1;
  return Then(
      ((int (*)(int, const char*, int, const char*))Next("renameat"))(from_dir, from, to_dir, to),
      kill_after);
}

int renameat2(int from_dir, const char* from, int to_dir, const char* to, unsigned int flags) {
  int kill_after = 0;
  if (ShouldFail(kRename, &kill_after)) return -1;
  return Then(((int (*)(int, const char*, int, const char*, unsigned int))Next("renameat2"))(
                  from_dir, from, to_dir, to, flags),
              kill_after);
}
