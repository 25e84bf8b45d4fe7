#include "cases.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Refuse absurd sizes from a damaged file before allocating. */
#define MAX_ELEMENTS (1ULL << 28)

typedef struct reader {
    FILE *file;
    int failed;
} reader;

static uint64_t read_le(reader *r, int bytes)
{
    unsigned char buffer[8];
    uint64_t value = 0;
    int k;
    if (r->failed || fread(buffer, 1, (size_t)bytes, r->file) != (size_t)bytes) {
        r->failed = 1;
        return 0;
    }
    for (k = bytes - 1; k >= 0; k--)
        value = value << 8 | buffer[k];
    return value;
}

static float *read_floats(reader *r, uint64_t count)
{
    float *values = calloc(count + 1, sizeof(float));
    uint64_t i;
    if (values == NULL) {
        r->failed = 1;
        return NULL;
    }
    for (i = 0; i < count; i++) {
        uint32_t bits = (uint32_t)read_le(r, 4);
        memcpy(&values[i], &bits, sizeof bits);
    }
    return values;
}

static int read_case(reader *r, stability_case *c)
{
    uint64_t name_length = read_le(r, 4), i;
    int has_texcoords, indexed, p, f;
    if (r->failed || name_length > 4096)
        return -1;
    c->name = calloc(name_length + 1, 1);
    if (c->name == NULL || fread(c->name, 1, name_length, r->file) != name_length)
        return -1;
    c->vertex_count = read_le(r, 8);
    has_texcoords = (int)read_le(r, 4);
    indexed = (int)read_le(r, 4);
    c->index_count = read_le(r, 8);
    if (r->failed || c->vertex_count > MAX_ELEMENTS || c->index_count > MAX_ELEMENTS)
        return -1;
    c->positions = read_floats(r, 3 * c->vertex_count);
    c->normals = read_floats(r, 3 * c->vertex_count);
    if (has_texcoords)
        c->texcoords = read_floats(r, 2 * c->vertex_count);
    if (indexed) {
        c->indices = calloc(c->index_count + 1, sizeof(uint32_t));
        if (c->indices == NULL)
            return -1;
        for (i = 0; i < c->index_count; i++)
            c->indices[i] = (uint32_t)read_le(r, 4);
    }
    for (p = 0; p < CASE_POLICIES; p++)
        for (f = 0; f < REPORT_FIELDS; f++)
            c->expected[p][f] = read_le(r, 8);
    return r->failed ? -1 : 0;
}

int cases_read(const char *path, stability_case **cases, uint32_t *count)
{
    reader r;
    char magic[4];
    uint32_t i, declared;
    const char *problem = NULL;
    *cases = NULL;
    *count = 0;
    r.failed = 0;
    r.file = fopen(path, "rb");
    if (r.file == NULL) {
        printf("cannot open case file %s\n", path);
        return -1;
    }
    if (fread(magic, 1, 4, r.file) != 4 || memcmp(magic, "TBC1", 4) != 0) {
        problem = "bad magic";
        goto fail;
    }
    declared = (uint32_t)read_le(&r, 4);
    if (r.failed || declared > MAX_ELEMENTS) {
        problem = "bad case count";
        goto fail;
    }
    *cases = calloc((size_t)declared + 1, sizeof(stability_case));
    if (*cases == NULL) {
        problem = "out of memory";
        goto fail;
    }
    /* count grows as cases are read, so cases_free releases exactly what was allocated. */
    for (i = 0; i < declared; i++) {
        *count = i + 1;
        if (read_case(&r, &(*cases)[i]) != 0) {
            problem = "a case is truncated or malformed";
            goto fail;
        }
    }
    if (fgetc(r.file) != EOF) {
        problem = "unexpected bytes after the last case";
        goto fail;
    }
    fclose(r.file);
    return 0;

fail:
    printf("%s: %s\n", path, problem);
    fclose(r.file);
    cases_free(*cases, *count);
    *cases = NULL;
    *count = 0;
    return -1;
}

void cases_free(stability_case *cases, uint32_t count)
{
    uint32_t i;
    if (cases == NULL)
        return;
    for (i = 0; i < count; i++) {
        free(cases[i].name);
        free(cases[i].positions);
        free(cases[i].normals);
        free(cases[i].texcoords);
        free(cases[i].indices);
    }
    free(cases);
}
