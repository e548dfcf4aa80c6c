/* method_table.c: the registry's table, the one place that lists every method. A method is added
 * by its own files (which define its `struct method` row) and one line here, in `restir list`
 * order (docs/ADDING_A_METHOD.md). */
#include "methods/method.h"

extern const struct method method_pt, method_ris_di, method_restir_di, method_restir_pt, method_area_restir,
    method_gpt, method_grad_after_restir, method_grestir_pt, method_restir_gi, method_ris_gi;

static const struct method *const table[] = {
    &method_pt,  &method_ris_di,  &method_restir_di,         &method_restir_pt,
    &method_area_restir, &method_gpt, &method_grad_after_restir, &method_grestir_pt,
    &method_restir_gi,   &method_ris_gi,
};

int method_count(void) { return (int)(sizeof(table) / sizeof(table[0])); }

const struct method *method_at(int k) { return k >= 0 && k < method_count() ? table[k] : NULL; }
