/* SPDX-License-Identifier: Apache-2.0 */
/*
 * corpus_json.c — typed access to the corpus's JSON; see corpus_json.h.
 */
#include "corpus_json.h"

#include <ctype.h>
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int cj_fail(cj_error *err, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    return 0;
}

void cj_path(char *out, size_t size, const char *parent, const char *key)
{
    if (parent[0] != '\0')
        snprintf(out, size, "%s.%s", parent, key);
    else
        snprintf(out, size, "%s", key);
}

/* Read the whole stream; a chunked loop rather than fseek/ftell so that pipes
 * and special files work too. Returns a NUL-terminated buffer or NULL. */
static char *read_all(FILE *f, size_t *length)
{
    size_t cap = 1 << 16, len = 0;
    char *buf = malloc(cap);
    if (buf == NULL)
        return NULL;
    for (;;) {
        size_t got;
        if (cap - len < 2) {
            char *bigger = realloc(buf, cap * 2);
            if (bigger == NULL) {
                free(buf);
                return NULL;
            }
            buf = bigger;
            cap *= 2;
        }
        got = fread(buf + len, 1, cap - len - 1, f);
        len += got;
        if (got == 0)
            break;
    }
    if (ferror(f)) {
        free(buf);
        return NULL;
    }
    buf[len] = '\0';
    *length = len;
    return buf;
}

/* 1-based line and column of offset `at` in text, for parse messages. */
static void line_and_column(const char *text, size_t at, int *line, int *column)
{
    size_t i;
    *line = 1;
    *column = 1;
    for (i = 0; i < at; i++) {
        if (text[i] == '\n') {
            (*line)++;
            *column = 1;
        } else {
            (*column)++;
        }
    }
}

cJSON *cj_load_file(const char *path, cj_error *err)
{
    FILE *f = fopen(path, "rb");
    char *text;
    size_t length = 0, stop;
    const char *end = NULL;
    cJSON *doc;
    int line, column;

    if (f == NULL) {
        cj_fail(err, "cannot open: %s", strerror(errno));
        return NULL;
    }
    text = read_all(f, &length);
    fclose(f);
    if (text == NULL) {
        cj_fail(err, "cannot read the file");
        return NULL;
    }
    /* Not require_null_terminated: trailing text is checked below so the
     * message can say where it starts. */
    doc = cJSON_ParseWithLengthOpts(text, length, &end, 0);
    stop = (end != NULL && end >= text && end <= text + length) ? (size_t)(end - text) : 0;
    if (doc == NULL) {
        line_and_column(text, stop, &line, &column);
        cj_fail(err, "invalid JSON at line %d, column %d", line, column);
        free(text);
        return NULL;
    }
    while (stop < length && isspace((unsigned char)text[stop]))
        stop++;
    if (stop < length) {
        line_and_column(text, stop, &line, &column);
        cj_fail(err, "unexpected text after the JSON value at line %d, column %d", line, column);
        cJSON_Delete(doc);
        free(text);
        return NULL;
    }
    free(text);
    return doc;
}

int cj_number_value(const cJSON *item, const char *path, double *out, cj_error *err)
{
    *out = 0.0; /* defined even on failure, so no caller can read garbage */
    if (cJSON_IsNumber(item)) {
        *out = item->valuedouble;
        return 1;
    }
    if (cJSON_IsString(item) && item->valuestring != NULL) {
        const char *s = item->valuestring;
        char *end = NULL;
        double value;
        /* strtod would skip leading blanks; the schema has none. */
        if (s[0] == '\0' || isspace((unsigned char)s[0]))
            return cj_fail(err, "field \"%s\": \"%s\" is not a number", path, s);
        value = strtod(s, &end);
        if (end == s || *end != '\0')
            return cj_fail(err, "field \"%s\": \"%s\" is not a number", path, s);
        *out = value;
        return 1;
    }
    if (item == NULL)
        return cj_fail(err, "field \"%s\" is missing", path);
    return cj_fail(err, "field \"%s\" must be a number or a number string", path);
}

int cj_number(const cJSON *obj, const char *parent, const char *key, double *out, cj_error *err)
{
    char path[160];
    cj_path(path, sizeof path, parent, key);
    return cj_number_value(cJSON_GetObjectItemCaseSensitive(obj, key), path, out, err);
}

int cj_number_or(const cJSON *obj, const char *parent, const char *key, double dflt,
                 double *out, cj_error *err)
{
    if (cJSON_GetObjectItemCaseSensitive(obj, key) == NULL) {
        *out = dflt;
        return 1;
    }
    return cj_number(obj, parent, key, out, err);
}

int cj_integer_value(const cJSON *item, const char *path, long long lo, long long hi,
                     long long *out, cj_error *err)
{
    double v;
    *out = 0;
    if (item == NULL)
        return cj_fail(err, "field \"%s\" is missing", path);
    if (!cJSON_IsNumber(item))
        return cj_fail(err, "field \"%s\" must be an integer", path);
    v = item->valuedouble;
    /* The range test comes first so the cast below is always defined. */
    if (!(v >= (double)lo && v <= (double)hi))
        return cj_fail(err, "field \"%s\": %.17g is out of range [%lld, %lld]", path, v, lo, hi);
    if (v != (double)(long long)v)
        return cj_fail(err, "field \"%s\": %.17g is not an integer", path, v);
    *out = (long long)v;
    return 1;
}

int cj_integer(const cJSON *obj, const char *parent, const char *key, long long lo,
               long long hi, long long *out, cj_error *err)
{
    char path[160];
    cj_path(path, sizeof path, parent, key);
    return cj_integer_value(cJSON_GetObjectItemCaseSensitive(obj, key), path, lo, hi, out, err);
}

int cj_string(const cJSON *obj, const char *parent, const char *key, const char **out,
              cj_error *err)
{
    char path[160];
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
    *out = "";
    cj_path(path, sizeof path, parent, key);
    if (item == NULL)
        return cj_fail(err, "field \"%s\" is missing", path);
    if (!cJSON_IsString(item) || item->valuestring == NULL)
        return cj_fail(err, "field \"%s\" must be a string", path);
    *out = item->valuestring;
    return 1;
}

/* Exactly n numbers in the array item; path names it in messages. */
static int numbers_of_array(const cJSON *item, const char *path, int n, double *out,
                            cj_error *err)
{
    const cJSON *element;
    int i = 0;
    if (item == NULL)
        return cj_fail(err, "field \"%s\" is missing", path);
    if (!cJSON_IsArray(item))
        return cj_fail(err, "field \"%s\" must be an array of %d numbers", path, n);
    if (cJSON_GetArraySize(item) != n)
        return cj_fail(err, "field \"%s\" must have %d numbers, has %d", path, n,
                       cJSON_GetArraySize(item));
    cJSON_ArrayForEach(element, item) {
        char element_path[192];
        snprintf(element_path, sizeof element_path, "%s[%d]", path, i);
        if (!cj_number_value(element, element_path, &out[i], err))
            return 0;
        i++;
    }
    return 1;
}

int cj_vector(const cJSON *obj, const char *parent, const char *key, int n, double *out,
              cj_error *err)
{
    char path[160];
    cj_path(path, sizeof path, parent, key);
    return numbers_of_array(cJSON_GetObjectItemCaseSensitive(obj, key), path, n, out, err);
}

int cj_rows(const cJSON *obj, const char *parent, const char *key, int width, double **out,
            int *rows, cj_error *err)
{
    char path[160];
    const cJSON *item = cJSON_GetObjectItemCaseSensitive(obj, key);
    const cJSON *row;
    double *values;
    int count, i = 0;

    *out = NULL;
    *rows = 0;
    cj_path(path, sizeof path, parent, key);
    if (item == NULL)
        return cj_fail(err, "field \"%s\" is missing", path);
    if (!cJSON_IsArray(item))
        return cj_fail(err, "field \"%s\" must be an array of [%d numbers]", path, width);
    count = cJSON_GetArraySize(item);
    values = malloc(((size_t)count * (size_t)width + 1) * sizeof *values);
    if (values == NULL)
        return cj_fail(err, "field \"%s\": out of memory", path);
    cJSON_ArrayForEach(row, item) {
        char row_path[192];
        snprintf(row_path, sizeof row_path, "%s[%d]", path, i);
        if (!numbers_of_array(row, row_path, width, values + (size_t)i * (size_t)width, err)) {
            free(values);
            return 0;
        }
        i++;
    }
    *out = values;
    *rows = count;
    return 1;
}
