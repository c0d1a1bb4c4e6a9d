/* param_help.c: the parameter list of the CLI help, from the parameter
 * table (param_help.h). */
#include "param_help.h"

#include "params_table.h"

/* "ncut_threshold" -> "ncut-threshold", the spelling flags usually take. */
static void flag_spelling(const char *name, char *flag, size_t size) {
    size_t i = 0;
    for (; name[i] && i + 1 < size; i++) flag[i] = name[i] == '_' ? '-' : name[i];
    flag[i] = 0;
}

/* The value placeholder after the flag (" N", " X", " auto|exact|approx"). */
static void metavar(const ps_param_spec *s, char *buf, size_t size) {
    buf[0] = 0;
    if (s->type == PS_PT_INT) snprintf(buf, size, " N");
    if (s->type == PS_PT_DOUBLE) snprintf(buf, size, " X");
    if (s->type == PS_PT_ENUM || s->type == PS_PT_LIST) {
        buf[0] = ' ';
        ps_params_join_choices(s->choices, s->type == PS_PT_ENUM ? "|" : ",", buf + 1, size - 1);
    }
}

static void print_values(FILE *out, const ps_param_spec *s) {
    switch (s->type) {
    case PS_PT_INT:
        fprintf(out, "integer in [%g, %g], default %s", s->min, s->max, s->default_text);
        break;
    case PS_PT_DOUBLE:
        fprintf(out, "number in [%g, %g], default %s", s->min, s->max, s->default_text);
        break;
    case PS_PT_BOOL:
        fprintf(out, "flag (or =true/false), default %s", s->default_text);
        break;
    case PS_PT_ENUM: fprintf(out, "default %s", s->default_text); break;
    case PS_PT_LIST:
        fprintf(out, "comma-separated, default %s", *s->default_text ? s->default_text : "none");
        break;
    }
}

void cli_print_param_help(FILE *out) {
    size_t count;
    const ps_param_spec *table = ps_param_table(&count);
    for (size_t i = 0; i < count; i++) {
        char flag[64], meta[128];
        flag_spelling(table[i].name, flag, sizeof flag);
        metavar(&table[i], meta, sizeof meta);
        fprintf(out, "  --%s%s\n      %s\n      (", flag, meta, table[i].help);
        print_values(out, &table[i]);
        fprintf(out, ")\n");
    }
}
