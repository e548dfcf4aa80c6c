/* fuzz_params.c: libFuzzer harness for `--params FILE` (experiments/settings_file.c): any bytes as
 * a settings file are read, applied as --set keys and validated, or refused with a message naming
 * the file; never a crash, a sanitizer report or a leak. */
#include <stdint.h>
#include <stdlib.h>

#include "core/check.h"
#include "experiments/settings_file.h"
#include "fuzz_file.h"
#include "methods/settings.h"
#include "render/params.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > (1u << 20))
        return 0;
    const char *path = fuzz_write("params.json", data, size);
    char msg[RESTIR_MSG_LEN];
    cJSON *o = settings_read_file(path, msg);
    if (!o) {
        fuzz_check_refusal(msg, sizeof msg, "params.json");
        return 0;
    }
    struct render_params p;
    render_params_defaults(&p);
    if (settings_apply_object(path, o, &p, msg) != 0)
        fuzz_check_refusal(msg, sizeof msg, "params.json");
    else if (render_params_validate(&p, msg) != 0)
        fuzz_check_refusal(msg, sizeof msg, NULL);
    cJSON_Delete(o);
    return 0;
}
