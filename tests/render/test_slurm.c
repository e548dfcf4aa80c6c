/* test_slurm.c: a study planned with --plan runs as a Slurm job array. The test starts
 * a single-node Slurm on this machine (munged with a generated key, slurmctld and slurmd on a
 * minimal slurm.conf: one node with this machine's cores, proctrack/linuxproc, no cgroups, state,
 * spool, logs and sockets in a temporary folder, ports chosen from the process id), submits
 * slurm.sh with `sbatch --wait`, merges and compares with the unsplit study, then stops the
 * daemons. Where Slurm is missing or cannot start, it says why and exits as skipped. */
#include <signal.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "cli_util.h"
#include "test_util.h"

#define STUDY "study --scene cornell --method restir-di --configs bitterli,compat --res 48x27 --frames 5 " \
              "--warmup 3 --runs 2 --ref-spp 32 --seed 21"

static char tmp[CLI_PATH_MAX], conf[2 * CLI_PATH_MAX];
static int started; /* daemons to stop at exit */

static int sh(const char *cmd)
{
    int st = system(cmd);
    return st == -1 || !WIFEXITED(st) ? -1 : WEXITSTATUS(st);
}

static int have(const char *tool)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "command -v %s >/dev/null 2>&1", tool);
    return sh(cmd) == 0;
}

/* Stops slurmd and slurmctld (scontrol shutdown), then whatever of them and munged still runs
 * (SIGTERM, then SIGKILL), and waits until every one is gone. */
static void stop_daemons(void)
{
    if (!started)
        return;
    char cmd[8 * CLI_PATH_MAX];
    snprintf(cmd, sizeof cmd,
             "pids=$(cat '%s/slurmctld.pid' '%s/slurmd.pid' '%s/munge/munged.pid' 2>/dev/null); "
             "SLURM_CONF='%s' scontrol shutdown >/dev/null 2>&1; "
             "alive() { for p in $pids; do kill -0 $p 2>/dev/null && return 0; done; return 1; }; "
             "for i in $(seq 20); do alive || break; sleep 0.25; done; "
             "for p in $pids; do kill $p 2>/dev/null; done; "
             "for i in $(seq 20); do alive || break; sleep 0.25; done; "
             "for p in $pids; do kill -9 $p 2>/dev/null; done; true",
             tmp, tmp, tmp, conf);
    sh(cmd);
    started = 0;
}

/* The daemons' logs' last lines, for a skip or failure message. */
static void log_tail(char *out, size_t n)
{
    char cmd[8 * CLI_PATH_MAX], path[2 * CLI_PATH_MAX];
    snprintf(path, sizeof path, "%s/logs_tail.txt", tmp);
    snprintf(cmd, sizeof cmd, "tail -n 3 '%s'/munge/munged.log '%s'/slurmctld.log '%s'/slurmd.log > '%s' 2>&1", tmp,
             tmp, tmp, path);
    sh(cmd);
    cli_read_text(path, out, n);
}

/* Starts munged, slurmctld and slurmd; returns 0 when the node is idle, else -1 with why. */
static int start_slurm(char *why, size_t n)
{
    char host[256] = "localhost", cmd[8 * CLI_PATH_MAX];
    gethostname(host, sizeof host - 1);
    char *dot = strchr(host, '.');
    if (dot)
        *dot = '\0';
    const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
    const int port = 20000 + (int)(getpid() % 20000) * 2;
    const char *user = getenv("USER") && *getenv("USER") ? getenv("USER") : "root";
    snprintf(conf, sizeof conf, "%s/slurm.conf", tmp);
    FILE *f = fopen(conf, "w");
    if (!f) {
        snprintf(why, n, "cannot write %.300s", conf);
        return -1;
    }
    fprintf(f,
            "ClusterName=restirtest\nSlurmctldHost=%s\nSlurmUser=%s\nSlurmdUser=%s\n"
            "SlurmctldPort=%d\nSlurmdPort=%d\nAuthType=auth/munge\nCredType=cred/munge\n"
            "AuthInfo=socket=%s/munge/munge.socket\nStateSaveLocation=%s/state\nSlurmdSpoolDir=%s/spool\n"
            "SlurmctldPidFile=%s/slurmctld.pid\nSlurmdPidFile=%s/slurmd.pid\nSlurmctldLogFile=%s/slurmctld.log\n"
            "SlurmdLogFile=%s/slurmd.log\nProctrackType=proctrack/linuxproc\nTaskPlugin=task/none\n"
            "JobAcctGatherType=jobacct_gather/none\nAccountingStorageType=accounting_storage/none\n"
            "SchedulerType=sched/backfill\nSelectType=select/cons_tres\nSelectTypeParameters=CR_CPU\n"
            "ReturnToService=2\nMpiDefault=none\nNodeName=%s CPUs=%ld State=UNKNOWN\n"
            "PartitionName=test Nodes=%s Default=YES MaxTime=INFINITE State=UP\n",
            host, user, user, port, port + 1, tmp, tmp, tmp, tmp, tmp, tmp, tmp, host, cpus, host);
    fclose(f);
    snprintf(cmd, sizeof cmd,
             "cd '%s' && mkdir -p state spool munge && chmod 700 munge && "
             "mungekey -c -k munge/munge.key -b 1024 >/dev/null 2>&1 && chmod 600 munge/munge.key && "
             "munged --force --key-file=munge/munge.key --socket='%s/munge/munge.socket' "
             "--pid-file='%s/munge/munged.pid' --log-file='%s/munge/munged.log' --seed-file='%s/munge/munged.seed'",
             tmp, tmp, tmp, tmp, tmp);
    started = 1;
    if (sh(cmd) != 0) {
        snprintf(why, n, "munged did not start");
        return -1;
    }
    snprintf(cmd, sizeof cmd, "SLURM_CONF='%s' slurmctld -c && sleep 1 && SLURM_CONF='%s' slurmd", conf, conf);
    if (sh(cmd) != 0) {
        snprintf(why, n, "slurmctld or slurmd did not start");
        return -1;
    }
    for (int t = 0; t < 60; t++) { /* up to 30 s for the node to register as idle */
        snprintf(cmd, sizeof cmd, "SLURM_CONF='%s' sinfo -h -o %%t 2>/dev/null | grep -q '^idle'", conf);
        if (sh(cmd) == 0)
            return 0;
        nanosleep(&(struct timespec){0, 500000000L}, NULL);
    }
    snprintf(why, n, "the node did not become idle within 30 s");
    return -1;
}


int main(void)
{
    static char err[CLI_ERR_MAX], why[4096], logs[4096];
    if (!cli_bin() || cli_make_temp_dir(tmp) != 0) {
        EXPECT(0, "cannot set up (RESTIR_BIN or temporary folder)");
        return test_finish();
    }
    static const char *const tools[] = {"munged", "mungekey", "slurmctld", "slurmd", "sbatch", "sinfo", "scontrol"};
    for (int i = 0; i < 7; i++)
        if (!have(tools[i])) {
            snprintf(why, sizeof why, "%s is not installed (Debian slurm-wlm and munge; make test-deps)", tools[i]);
            cli_remove_tree(tmp);
            return test_skip(why);
        }
    atexit(stop_daemons);
    if (start_slurm(why, sizeof why) != 0) {
        log_tail(logs, sizeof logs);
        stop_daemons();
        printf("Slurm could not start: %s\n%s\n", why, logs);
        cli_remove_tree(tmp);
        return test_skip("Slurm could not start on this machine (see above)");
    }
    printf("single-node Slurm up (%s)\n", conf);

    char unsplit[2 * CLI_PATH_MAX], plan[2 * CLI_PATH_MAX], args[6 * CLI_PATH_MAX];
    snprintf(unsplit, sizeof unsplit, "%s/study", tmp);
    snprintf(plan, sizeof plan, "%s/plan", tmp);
    snprintf(args, sizeof args, STUDY " --out '%s'", unsplit);
    EXPECT(cli_run(tmp, args, err) == 0, "unsplit study: %s", err);
    snprintf(args, sizeof args, STUDY " --plan '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "study --plan: %s", err);
    const time_t t0 = time(NULL);
    snprintf(args, sizeof args, "SLURM_CONF='%s' timeout 300 sbatch --wait --quiet '%s/slurm.sh'", conf, plan);
    int rc = sh(args);
    EXPECT(rc == 0, "sbatch --wait: exit %d (logs in %s/runs/logs)", rc, plan);
    printf("the array of 5 jobs ran under Slurm in %ld s\n", (long)(time(NULL) - t0));
    snprintf(args, sizeof args, "study --merge '%s'", plan);
    EXPECT(cli_run(tmp, args, err) == 0, "study --merge: %s", err);
    static char a[1 << 16], b[1 << 16];
    char pa[3 * CLI_PATH_MAX], pb[3 * CLI_PATH_MAX];
    snprintf(pa, sizeof pa, "%s/study.csv", unsplit);
    snprintf(pb, sizeof pb, "%s/study.csv", plan);
    cli_csv_without_columns(pa, 8, 1000, a, sizeof a); /* all but the pass times */
    cli_csv_without_columns(pb, 8, 1000, b, sizeof b); /* all but the pass times */
    EXPECT(a[0] && strcmp(a, b) == 0, "study merged from Slurm differs:\n%s\nvs\n%s", a, b);
    long size = 0;
    snprintf(pa, sizeof pa, "%s/strip.png", unsplit);
    snprintf(pb, sizeof pb, "%s/strip.png", plan);
    EXPECT(cli_files_equal(pa, pb, &size) == 1, "strip.png merged from Slurm differs");
    printf("merged from the Slurm array, equal to the unsplit study (all but the times):\n%s", b);
    stop_daemons();
    EXPECT(cli_remove_tree(tmp) == 0, "cannot remove %s", tmp);
    return test_finish();
}
