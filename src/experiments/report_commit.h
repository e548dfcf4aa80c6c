/* report_commit.h: the commit reports name: RESTIR_GIT_COMMIT, RESTIR_GIT_DIRTY and RESTIR_BUILD_TYPE
 * of the generated restir_version.h, which a step of every build rewrites when the commit or the
 * tree's state changes (cmake/version.cmake); "unknown" where the build has no such header. */
#ifndef RESTIR_EXPERIMENTS_REPORT_COMMIT_H
#define RESTIR_EXPERIMENTS_REPORT_COMMIT_H

#ifdef RESTIR_HAVE_VERSION_HEADER
#include <restir_version.h>
#endif

#ifndef RESTIR_GIT_COMMIT
#define RESTIR_GIT_COMMIT "unknown"
#endif
#ifndef RESTIR_GIT_DIRTY
#define RESTIR_GIT_DIRTY 0
#endif
#ifndef RESTIR_BUILD_TYPE
#define RESTIR_BUILD_TYPE "unknown"
#endif

#endif
