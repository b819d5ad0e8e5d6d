/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_json.h — typed access to the corpus's JSON (cJSON underneath).
 *
 * The corpus writes a number either as a JSON number or as a string that
 * strtod() reads whole ("inf", "-inf", "nan", a C99 hex float such as
 * "0x1.8p+1"), because JSON has no infinities and decimal text cannot promise
 * a bit-exact double. Every getter below accepts both forms.
 *
 * Getters take the object, a key and the path of the object ("" at the
 * top, "shape", "expect.hits[2]") so that a malformed field is reported by
 * its full name. They return 1 on success and 0 on failure, with the reason
 * in *err. Optional fields take the given default when the key is absent.
 */
#ifndef ISECT_CORPUS_JSON_H
#define ISECT_CORPUS_JSON_H

#include <cjson/cJSON.h>

#include <stddef.h>

typedef struct cj_error {
    char message[400];
} cj_error;

/* Load and parse a whole file. NULL with a message (I/O error, or the line
 * and column where parsing stopped) on failure; free with cJSON_Delete(). */
cJSON *cj_load_file(const char *path, cj_error *err);

/* Record a message in *err; always returns 0 so callers can `return cj_fail(...)`. */
int cj_fail(cj_error *err, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;

/* "parent.key", or "key" when parent is empty. */
void cj_path(char *out, size_t size, const char *parent, const char *key);

/* A corpus number held by item itself (used for array elements). */
int cj_number_value(const cJSON *item, const char *path, double *out, cj_error *err);

/* Required number. */
int cj_number(const cJSON *obj, const char *parent, const char *key, double *out, cj_error *err);

/* Number that defaults to dflt when the key is absent. */
int cj_number_or(const cJSON *obj, const char *parent, const char *key, double dflt,
                 double *out, cj_error *err);

/* Required integer in [lo, hi] (an integral JSON number). */
int cj_integer(const cJSON *obj, const char *parent, const char *key, long long lo,
               long long hi, long long *out, cj_error *err);

/* Integer held by item itself, in [lo, hi]. */
int cj_integer_value(const cJSON *item, const char *path, long long lo, long long hi,
                     long long *out, cj_error *err);

/* Required string; the pointer lives as long as the document. */
int cj_string(const cJSON *obj, const char *parent, const char *key, const char **out,
              cj_error *err);

/* Required array of exactly n numbers. */
int cj_vector(const cJSON *obj, const char *parent, const char *key, int n, double *out,
              cj_error *err);

/* Required array of rows, each an array of exactly `width` numbers, of any
 * length (bad-input cases pass short polygons as they are). *out is a
 * malloc'd rows*width array, never NULL even for zero rows, so it can be
 * handed to the library as a valid pointer; free() it. */
int cj_rows(const cJSON *obj, const char *parent, const char *key, int width, double **out,
            int *rows, cj_error *err);

#endif /* ISECT_CORPUS_JSON_H */
