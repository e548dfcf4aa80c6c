/* scene_import_guard.c: assimp's first read of a file in a forked child (scene_import_guard.h).
 * The child does nothing but the import and _exit, so the state it inherits (other threads' locks,
 * open streams) is never touched; glibc's fork makes malloc usable in it. */
#include "scene/scene_import_guard.h"

#include <assimp/cimport.h>
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include "core/check.h"

/* The child's exit statuses: assimp read the file, or refused it with a message. */
enum { GUARD_READ = 0, GUARD_REFUSED = 3 };

int import_guard_probe(const char *path, unsigned flags, char *msg)
{
    struct stat st;
    const double mb = stat(path, &st) == 0 ? (double)st.st_size / (1 << 20) : 0.0;
    const double limit = IMPORT_GUARD_BASE_SECONDS + IMPORT_GUARD_SECONDS_PER_MB * mb;
    const unsigned seconds = limit < 86400.0 ? (unsigned)limit : 86400u;
    fflush(NULL); /* nothing buffered is written twice */
    const pid_t pid = fork();
    if (pid < 0) /* no process to spare: import unguarded rather than refuse a good file */
        return 0;
    if (pid == 0) {
        /* a fault or the alarm ends the child by its signal, not through a handler the parent
         * installed (a sanitizer's or a fuzzer's would report it as the parent's own and exit with
         * a code, or ignore the alarm) */
        static const int faults[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGALRM};
        for (size_t k = 0; k < sizeof faults / sizeof faults[0]; k++)
            signal(faults[k], SIG_DFL);
        alarm(seconds);
        const struct aiScene *ai = aiImportFile(path, flags);
        _exit(ai ? GUARD_READ : GUARD_REFUSED);
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
        ;
    if (WIFEXITED(status) && (WEXITSTATUS(status) == GUARD_READ || WEXITSTATUS(status) == GUARD_REFUSED))
        return 0;
    if (!WIFSIGNALED(status)) { /* any other way out is a failure inside assimp */
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: assimp failed reading it (exit status %d); refused", path,
                 WIFEXITED(status) ? WEXITSTATUS(status) : -1);
        return -1;
    }
    const int sig = WTERMSIG(status);
    if (sig == SIGALRM)
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: assimp did not finish reading it within %u s; refused", path,
                 seconds);
    else
        snprintf(msg, RESTIR_MSG_LEN, "%.300s: assimp crashed reading it (signal %d, %s); refused", path, sig,
                 strsignal(sig));
    return -1;
}
