/* report_commit.h: the commit reports name (CMake defines RESTIR_GIT_COMMIT for the restir
 * target when it configures inside a git checkout). */
#ifndef RESTIR_EXPERIMENTS_REPORT_COMMIT_H
#define RESTIR_EXPERIMENTS_REPORT_COMMIT_H

#ifndef RESTIR_GIT_COMMIT
#define RESTIR_GIT_COMMIT "unknown"
#endif

#endif
