/* fuzz_plan.c: libFuzzer harness for plan folders (experiments/plan.c): the first byte picks what
 * the rest is, a plan.json read by plan_load (which merges and jobs trust for their arguments and
 * outputs) or a job's result blob read by plan_blob_read (magic, plan id, size, checksum). Any
 * input is loaded or refused with a message naming the folder or file; never a crash, a sanitizer
 * report or a leak. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/check.h"
#include "experiments/plan.h"
#include "fuzz_file.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > (1u << 20))
        return 0;
    char msg[RESTIR_MSG_LEN];
    if (data[0] & 1) {
        fuzz_write("plan.json", data + 1, size - 1);
        struct plan p;
        if (plan_load(fuzz_dir(), &p, msg) == 0) {
            char out[PLAN_PATH_MAX + 200];
            for (int k = 0; k < p.n_jobs; k++)
                plan_output_path(&p, k, out, sizeof out);
            plan_free(&p);
        } else
            fuzz_check_refusal(msg, sizeof msg, "restir-fuzz-");
        return 0;
    }
    const char *path = fuzz_write("job.bin", data + 1, size - 1);
    void *payload = NULL;
    size_t n = 0;
    const int rc = plan_blob_read(path, "RCOMPAR4", 0x1234abcdull, &payload, &n, msg);
    if (rc == 0)
        free(payload);
    else if (rc < 0)
        fuzz_check_refusal(msg, sizeof msg, "job.bin");
    return 0;
}
