/* csv_table.h: reading back the CSV files the commands write (csv_table.c), for `restir evaluate`'s
 * tables. Must never write files or know what the columns mean. */
#ifndef RESTIR_EXPERIMENTS_CSV_TABLE_H
#define RESTIR_EXPERIMENTS_CSV_TABLE_H

/* A CSV file as cells: row 0 is the header; fields may be quoted ("", doubled quotes inside). */
struct csv_table {
    int ncol, nrow; /* nrow counts the data rows, not the header */
    char **cell;    /* (nrow + 1) * ncol */
    char *text;
};

/* Reads path. Returns 0, or -1 with msg (RESTIR_MSG_LEN): missing, or a row of another width. */
int csv_table_read(const char *path, struct csv_table *t, char *msg);
void csv_table_free(struct csv_table *t);
/* Data row (0-based) whose first field is `key`, or -1. */
int csv_table_find(const struct csv_table *t, const char *key);
/* The number in data row `row`, column `col` (by header name); NaN when either is missing or the
 * field is empty or not a number. */
double csv_table_num(const struct csv_table *t, int row, const char *col);

#endif
