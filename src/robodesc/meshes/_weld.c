/* Welding mesh corners into shared points, and flat face normals, for the USD emitter.
 *
 * numpy has no hash table, so robodesc's numpy weld sorts 64-bit hashes of every corner; a hash
 * table here does the same in one pass, about five times faster. Both define the result the same
 * way, so they agree bit for bit (tests/usd/test_mesh_native.py holds them to it):
 *
 * weld(rows, corners) -> (first, indices)
 *     rows: a C-contiguous buffer of float64 triples; corners: a buffer of int64 row numbers, or
 *     None for every row in order. Corners whose triples are equal bit for bit (so 0.0 and -0.0
 *     stay apart) share a point; points are numbered by their first corner. Returns bytearrays of
 *     int64 ``first`` (the row of each point, in point order) and int32 ``indices`` (each corner's
 *     point). Raises ValueError for a corner outside the rows.
 *
 * face_normals(points, triangles) -> bytearray
 *     points: float64 triples; triangles: int32 triples of point numbers, in range. The unit normal
 *     of each triangle as float32 triples: the cross product of its two edges from the first
 *     corner, divided by its length ((x*x + y*y) + z*z, as numpy.linalg.norm sums it), 0 for a
 *     degenerate triangle, never -0. The arithmetic is numpy's, operation for operation, and the
 *     build turns off FMA contraction (setup.py), so the result is numpy's bit for bit.
 *
 * The rest lets robodesc.emit.mesh_data finish a mesh without importing numpy (about 0.1 s, more
 * than converting a small robot); each function says which numpy code it matches:
 *     stl(data)                       binary STL -> welded float64 points, int32 triangles
 *     weld_take(rows, corners)        weld(), then the welded points themselves
 *     columns(values, ...)            COLLADA accessor -> float32 positions, NaN -> 0
 *     place(points, matrix, unit)     COLLADA instance -> float64 points (rounded to float32 once)
 *     shift(values, offset)           int64 indices + offset
 *     finish(points, triangles, ...)  scale, mirror flip, normals, float32 points, extent
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* MurmurHash3's 64-bit finaliser: every output bit depends on every input bit. Coordinates widened
 * from float32 have 29 zero low bits, which a weaker mix turns into collisions. */
static uint64_t mix64(uint64_t x) {
    x ^= x >> 33;
    x *= 0xFF51AFD7ED558CCDULL;
    x ^= x >> 33;
    x *= 0xC4CEB9FE1A85EC53ULL;
    x ^= x >> 33;
    return x;
}

static uint64_t hash_row(const uint64_t *row) {
    return mix64(mix64(mix64(row[2]) ^ row[1]) ^ row[0]);
}

static int get_buffer(PyObject *object, Py_buffer *view, const char *what) {
    if (PyObject_GetBuffer(object, view, PyBUF_C_CONTIGUOUS) != 0) {
        return -1;
    }
    if (view->len % 8 != 0) {
        PyBuffer_Release(view);
        PyErr_Format(PyExc_ValueError, "%s: buffer length is not a multiple of 8 bytes", what);
        return -1;
    }
    return 0;
}

/* The weld of ``count`` corners (row numbers ``corners``, or every row in order when NULL) into
 * ``first_rows`` (the row of each point, in point order) and ``out`` (each corner's point); both
 * hold ``count`` values. Returns the number of points, or -1 with an exception set. */
static Py_ssize_t weld_rows(const uint64_t *rows, Py_ssize_t row_count, const int64_t *corners, Py_ssize_t count,
                            int64_t *first_rows, int32_t *out) {
    if (count > INT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "too many corners for 32-bit indices");
        return -1;
    }
    /* Open addressing at a load factor of at most one half; slots hold point numbers, -1 empty. */
    Py_ssize_t capacity = 16;
    while (capacity < 2 * count) {
        capacity *= 2;
    }
    uint64_t mask = (uint64_t)capacity - 1;
    int32_t *table = PyMem_Malloc(capacity * sizeof(int32_t));
    if (table == NULL) {
        PyErr_NoMemory();
        return -1;
    }
    memset(table, 0xff, capacity * sizeof(int32_t));
    int32_t points = 0;
    for (Py_ssize_t k = 0; k < count; k++) {
        int64_t r = corners != NULL ? corners[k] : (int64_t)k;
        if (r < 0 || r >= row_count) {
            PyErr_Format(PyExc_ValueError, "corner %zd refers to row %lld of %zd", k, (long long)r, row_count);
            PyMem_Free(table);
            return -1;
        }
        const uint64_t *row = rows + 3 * r;
        uint64_t slot = hash_row(row) & mask;
        while (1) {
            int32_t point = table[slot];
            if (point < 0) {
                table[slot] = points;
                first_rows[points] = r;
                out[k] = points++;
                break;
            }
            if (memcmp(rows + 3 * first_rows[point], row, 24) == 0) {
                out[k] = point;
                break;
            }
            slot = (slot + 1) & mask;
        }
    }
    PyMem_Free(table);
    return points;
}

static PyObject *weld(PyObject *self, PyObject *args) {
    PyObject *rows_object, *corners_object;
    if (!PyArg_ParseTuple(args, "OO", &rows_object, &corners_object)) {
        return NULL;
    }
    Py_buffer rows_view, corners_view;
    if (get_buffer(rows_object, &rows_view, "rows") != 0) {
        return NULL;
    }
    int have_corners = corners_object != Py_None;
    if (have_corners && get_buffer(corners_object, &corners_view, "corners") != 0) {
        PyBuffer_Release(&rows_view);
        return NULL;
    }
    Py_ssize_t row_count = rows_view.len / 24;
    const int64_t *corners = have_corners ? (const int64_t *)corners_view.buf : NULL;
    Py_ssize_t count = have_corners ? corners_view.len / 8 : row_count;
    PyObject *result = NULL;
    PyObject *first = PyByteArray_FromStringAndSize(NULL, count * 8);
    PyObject *indices = PyByteArray_FromStringAndSize(NULL, count * 4);
    if (first != NULL && indices != NULL) {
        Py_ssize_t points = weld_rows((const uint64_t *)rows_view.buf, row_count, corners, count,
                                      (int64_t *)PyByteArray_AS_STRING(first), (int32_t *)PyByteArray_AS_STRING(indices));
        if (points >= 0 && PyByteArray_Resize(first, points * 8) == 0) {
            result = PyTuple_Pack(2, first, indices);
        }
    }
    Py_XDECREF(first);
    Py_XDECREF(indices);
    PyBuffer_Release(&rows_view);
    if (have_corners) {
        PyBuffer_Release(&corners_view);
    }
    return result;
}

/* A binary STL's triangles, welded: its corners widened to float64 (as numpy's astype does) and
 * merged by weld_rows. Returns (points float64, indices int32), or None when the size does not
 * match the triangle count (an ASCII file or a broken one: the caller's reader decides). */
static PyObject *stl(PyObject *self, PyObject *args) {
    Py_buffer view;
    if (!PyArg_ParseTuple(args, "y*", &view)) {
        return NULL;
    }
    PyObject *result = NULL, *points = NULL, *indices = NULL;
    double *corners = NULL;
    int64_t *first = NULL;
    const unsigned char *data = (const unsigned char *)view.buf;
    if (view.len < 84) {
        result = Py_NewRef(Py_None);
        goto done;
    }
    uint32_t triangles;
    memcpy(&triangles, data + 80, 4); /* little-endian hosts only: setup.py builds for those */
    if (84 + (Py_ssize_t)triangles * 50 != view.len) {
        result = Py_NewRef(Py_None);
        goto done;
    }
    Py_ssize_t count = (Py_ssize_t)triangles * 3;
    corners = PyMem_Malloc((count ? count : 1) * 24);
    first = PyMem_Malloc((count ? count : 1) * 8);
    indices = PyByteArray_FromStringAndSize(NULL, count * 4);
    if (corners == NULL || first == NULL || indices == NULL) {
        if (indices != NULL) {
            PyErr_NoMemory();
        }
        goto done;
    }
    for (Py_ssize_t t = 0; t < (Py_ssize_t)triangles; t++) {
        const unsigned char *record = data + 84 + 50 * t + 12; /* after the facet normal */
        for (int j = 0; j < 9; j++) {
            float value;
            memcpy(&value, record + 4 * j, 4);
            corners[9 * t + j] = (double)value;
        }
    }
    Py_ssize_t made = weld_rows((const uint64_t *)corners, count, NULL, count, first, (int32_t *)PyByteArray_AS_STRING(indices));
    if (made < 0) {
        goto done;
    }
    points = PyByteArray_FromStringAndSize(NULL, made * 24);
    if (points == NULL) {
        goto done;
    }
    double *out = (double *)PyByteArray_AS_STRING(points);
    for (Py_ssize_t p = 0; p < made; p++) {
        memcpy(out + 3 * p, corners + 3 * first[p], 24);
    }
    result = PyTuple_Pack(2, points, indices);
done:
    PyMem_Free(corners);
    PyMem_Free(first);
    Py_XDECREF(points);
    Py_XDECREF(indices);
    PyBuffer_Release(&view);
    return result;
}

/* The float32 unit normal of triangle (a, b, c), numpy's arithmetic operation for operation. */
static void unit_normal(const double *a, const double *b, const double *c, float *normal) {
    double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    /* numpy.cross's terms, in its order. */
    double n[3] = {
        e1[1] * e2[2] - e1[2] * e2[1],
        e1[2] * e2[0] - e1[0] * e2[2],
        e1[0] * e2[1] - e1[1] * e2[0],
    };
    double length = sqrt((n[0] * n[0] + n[1] * n[1]) + n[2] * n[2]);
    for (int j = 0; j < 3; j++) {
        /* A degenerate (or NaN-length) triangle gets 0; "+ 0.0" turns -0.0 into 0.0. */
        double v = length > 0 ? n[j] / length : 0.0;
        normal[j] = (float)(v + 0.0);
    }
}

/* The float64 points and int32 triangles of face_normals() and finish(); 0 on success. */
static int get_mesh(PyObject *points, PyObject *triangles, Py_buffer *points_view, Py_buffer *triangles_view) {
    if (get_buffer(points, points_view, "points") != 0) {
        return -1;
    }
    if (PyObject_GetBuffer(triangles, triangles_view, PyBUF_C_CONTIGUOUS) != 0) {
        PyBuffer_Release(points_view);
        return -1;
    }
    return 0;
}

static PyObject *face_normals(PyObject *self, PyObject *args) {
    PyObject *points_object, *triangles_object;
    if (!PyArg_ParseTuple(args, "OO", &points_object, &triangles_object)) {
        return NULL;
    }
    Py_buffer points_view, triangles_view;
    if (get_mesh(points_object, triangles_object, &points_view, &triangles_view) != 0) {
        return NULL;
    }
    const double *p = (const double *)points_view.buf;
    Py_ssize_t point_count = points_view.len / 24;
    const int32_t *tri = (const int32_t *)triangles_view.buf;
    Py_ssize_t count = triangles_view.len / 12;
    PyObject *out = PyByteArray_FromStringAndSize(NULL, count * 12);
    if (out != NULL) {
        float *normal = (float *)PyByteArray_AS_STRING(out);
        for (Py_ssize_t t = 0; t < count; t++) {
            int32_t i0 = tri[3 * t], i1 = tri[3 * t + 1], i2 = tri[3 * t + 2];
            if (i0 < 0 || i1 < 0 || i2 < 0 || i0 >= point_count || i1 >= point_count || i2 >= point_count) {
                Py_CLEAR(out);
                PyErr_Format(PyExc_ValueError, "triangle %zd refers to a point out of range", t);
                break;
            }
            unit_normal(p + 3 * i0, p + 3 * i1, p + 3 * i2, normal + 3 * t);
        }
    }
    PyBuffer_Release(&points_view);
    PyBuffer_Release(&triangles_view);
    return out;
}


/* What a UsdGeom.Mesh needs from welded float64 points and int32 triangles, as usd_meshio's numpy
 * code computes it: the points scaled by (sx, sy, sz) when a scale is given (float64 products),
 * the winding reversed when ``flip`` (a mirroring scale), the float32 unit normal of each triangle
 * of the scaled points, the points rounded to float32, and their extent (per axis minimum and
 * maximum; NaN when any coordinate on that axis is NaN, as numpy's min and max give; never -0).
 * Returns (points float32, indices int32, normals float32, (min x, y, z, max x, y, z)). */
static PyObject *finish(PyObject *self, PyObject *args) {
    PyObject *points_object, *triangles_object, *scale_object;
    int flip;
    if (!PyArg_ParseTuple(args, "OOOp", &points_object, &triangles_object, &scale_object, &flip)) {
        return NULL;
    }
    double scale[3] = {1.0, 1.0, 1.0};
    int scaled = scale_object != Py_None;
    if (scaled && !PyArg_ParseTuple(scale_object, "ddd", &scale[0], &scale[1], &scale[2])) {
        return NULL;
    }
    Py_buffer points_view, triangles_view;
    if (get_mesh(points_object, triangles_object, &points_view, &triangles_view) != 0) {
        return NULL;
    }
    Py_ssize_t point_count = points_view.len / 24;
    Py_ssize_t triangle_count = triangles_view.len / 12;
    const int32_t *tri = (const int32_t *)triangles_view.buf;
    PyObject *result = NULL, *points = NULL, *indices = NULL, *normals = NULL, *extent = NULL;
    double *moved = NULL;
    const double *p = (const double *)points_view.buf;
    if (scaled) {
        moved = PyMem_Malloc((point_count ? point_count : 1) * 24);
        if (moved == NULL) {
            PyErr_NoMemory();
            goto done;
        }
        for (Py_ssize_t i = 0; i < point_count; i++) {
            for (int j = 0; j < 3; j++) {
                moved[3 * i + j] = p[3 * i + j] * scale[j];
            }
        }
        p = moved;
    }
    points = PyByteArray_FromStringAndSize(NULL, point_count * 12);
    indices = PyByteArray_FromStringAndSize(NULL, triangle_count * 12);
    normals = PyByteArray_FromStringAndSize(NULL, triangle_count * 12);
    if (points == NULL || indices == NULL || normals == NULL) {
        goto done;
    }
    int32_t *out_tri = (int32_t *)PyByteArray_AS_STRING(indices);
    float *normal = (float *)PyByteArray_AS_STRING(normals);
    for (Py_ssize_t t = 0; t < triangle_count; t++) {
        int32_t i0 = tri[3 * t], i1 = tri[3 * t + 1], i2 = tri[3 * t + 2];
        if (i0 < 0 || i1 < 0 || i2 < 0 || i0 >= point_count || i1 >= point_count || i2 >= point_count) {
            PyErr_Format(PyExc_ValueError, "triangle %zd refers to a point out of range", t);
            goto done;
        }
        if (flip) {
            int32_t swap = i0;
            i0 = i2;
            i2 = swap;
        }
        out_tri[3 * t] = i0;
        out_tri[3 * t + 1] = i1;
        out_tri[3 * t + 2] = i2;
        unit_normal(p + 3 * i0, p + 3 * i1, p + 3 * i2, normal + 3 * t);
    }
    float *out = (float *)PyByteArray_AS_STRING(points);
    float low[3] = {INFINITY, INFINITY, INFINITY}, high[3] = {-INFINITY, -INFINITY, -INFINITY};
    int nan[3] = {0, 0, 0};
    for (Py_ssize_t i = 0; i < 3 * point_count; i++) {
        float v = (float)p[i];
        int j = (int)(i % 3);
        out[i] = v;
        if (v != v) {
            nan[j] = 1;
        } else {
            low[j] = v < low[j] ? v : low[j];
            high[j] = v > high[j] ? v : high[j];
        }
    }
    for (int j = 0; j < 3; j++) {
        if (nan[j]) {
            low[j] = high[j] = NAN;
        }
        /* 0.0 and -0.0 tie; which one a minimum keeps is the implementation's choice (numpy's
         * SIMD loops differ from a plain scan), so the extent never has -0. */
        low[j] += 0.0f;
        high[j] += 0.0f;
    }
    extent = Py_BuildValue("(dddddd)", (double)low[0], (double)low[1], (double)low[2], (double)high[0], (double)high[1],
                           (double)high[2]);
    if (extent != NULL) {
        result = PyTuple_Pack(4, points, indices, normals, extent);
    }
done:
    PyMem_Free(moved);
    Py_XDECREF(points);
    Py_XDECREF(indices);
    Py_XDECREF(normals);
    Py_XDECREF(extent);
    PyBuffer_Release(&points_view);
    PyBuffer_Release(&triangles_view);
    return result;
}

/* weld(rows, corners), then the welded points themselves: (points float64, indices int32). */
static PyObject *weld_take(PyObject *self, PyObject *args) {
    PyObject *welded = weld(self, args);
    if (welded == NULL) {
        return NULL;
    }
    PyObject *rows_object = PyTuple_GET_ITEM(args, 0);
    PyObject *first = PyTuple_GET_ITEM(welded, 0);
    Py_buffer rows_view;
    if (get_buffer(rows_object, &rows_view, "rows") != 0) {
        Py_DECREF(welded);
        return NULL;
    }
    Py_ssize_t count = PyByteArray_GET_SIZE(first) / 8;
    const int64_t *picks = (const int64_t *)PyByteArray_AS_STRING(first);
    PyObject *points = PyByteArray_FromStringAndSize(NULL, count * 24);
    PyObject *result = NULL;
    if (points != NULL) {
        double *out = (double *)PyByteArray_AS_STRING(points);
        const double *rows = (const double *)rows_view.buf;
        for (Py_ssize_t i = 0; i < count; i++) {
            memcpy(out + 3 * i, rows + 3 * picks[i], 24);
        }
        result = PyTuple_Pack(2, points, PyTuple_GET_ITEM(welded, 1));
        Py_DECREF(points);
    }
    PyBuffer_Release(&rows_view);
    Py_DECREF(welded);
    return result;
}

/* COLLADA positions: ``count`` points of three float64 values at ``offset + i * stride + column``
 * for the three columns, rounded to float32, NaN replaced by 0 (pycollada's rule).
 * The caller checks the bounds; they are checked again here. */
static PyObject *columns(PyObject *self, PyObject *args) {
    Py_buffer view;
    Py_ssize_t offset, stride, count, c0, c1, c2;
    if (!PyArg_ParseTuple(args, "y*nnn(nnn)", &view, &offset, &stride, &count, &c0, &c1, &c2)) {
        return NULL;
    }
    Py_ssize_t available = view.len / 8;
    Py_ssize_t top = c0 > c1 ? (c0 > c2 ? c0 : c2) : (c1 > c2 ? c1 : c2);
    if (offset < 0 || stride <= 0 || count < 0 || c0 < 0 || c1 < 0 || c2 < 0 || top >= stride ||
        (count > 0 && offset + (count - 1) * stride + top >= available)) {
        PyBuffer_Release(&view);
        PyErr_SetString(PyExc_ValueError, "positions outside the array");
        return NULL;
    }
    PyObject *out = PyByteArray_FromStringAndSize(NULL, count * 12);
    if (out != NULL) {
        const double *values = (const double *)view.buf;
        float *points = (float *)PyByteArray_AS_STRING(out);
        Py_ssize_t picks[3] = {c0, c1, c2};
        for (Py_ssize_t i = 0; i < count; i++) {
            for (int j = 0; j < 3; j++) {
                float v = (float)values[offset + i * stride + picks[j]];
                points[3 * i + j] = v != v ? 0.0f : v;
            }
        }
    }
    PyBuffer_Release(&view);
    return out;
}

/* float32 points placed by a node transform: each coordinate ((r0 x + r1 y) + r2 z) + t in double,
 * rounded once to float32, then widened and multiplied by ``unit`` (the file's metres per unit;
 * 1.0 leaves it). ``matrix`` is the 3x4 row-major upper part of the 4x4. Returns float64 triples. */
static PyObject *place(PyObject *self, PyObject *args) {
    Py_buffer view;
    double m[12], unit;
    if (!PyArg_ParseTuple(args, "y*(dddddddddddd)d", &view, &m[0], &m[1], &m[2], &m[3], &m[4], &m[5], &m[6], &m[7],
                          &m[8], &m[9], &m[10], &m[11], &unit)) {
        return NULL;
    }
    Py_ssize_t count = view.len / 12;
    PyObject *out = PyByteArray_FromStringAndSize(NULL, count * 24);
    if (out != NULL) {
        const float *p = (const float *)view.buf;
        double *placed = (double *)PyByteArray_AS_STRING(out);
        for (Py_ssize_t i = 0; i < count; i++) {
            double x = p[3 * i], y = p[3 * i + 1], z = p[3 * i + 2];
            for (int j = 0; j < 3; j++) {
                const double *r = m + 4 * j;
                float v = (float)(((r[0] * x + r[1] * y) + r[2] * z) + r[3]);
                placed[3 * i + j] = unit == 1.0 ? (double)v : (double)v * unit;
            }
        }
    }
    PyBuffer_Release(&view);
    return out;
}

/* int64 values plus ``offset``. */
static PyObject *shift(PyObject *self, PyObject *args) {
    Py_buffer view;
    long long offset;
    if (!PyArg_ParseTuple(args, "y*L", &view, &offset)) {
        return NULL;
    }
    Py_ssize_t count = view.len / 8;
    PyObject *out = PyByteArray_FromStringAndSize(NULL, count * 8);
    if (out != NULL) {
        const int64_t *values = (const int64_t *)view.buf;
        int64_t *shifted = (int64_t *)PyByteArray_AS_STRING(out);
        for (Py_ssize_t i = 0; i < count; i++) {
            shifted[i] = values[i] + (int64_t)offset;
        }
    }
    PyBuffer_Release(&view);
    return out;
}

/* (min, max) of int64 values; None when there are none. */
static PyObject *bounds(PyObject *self, PyObject *args) {
    Py_buffer view;
    if (!PyArg_ParseTuple(args, "y*", &view)) {
        return NULL;
    }
    Py_ssize_t count = view.len / 8;
    if (count == 0) {
        PyBuffer_Release(&view);
        Py_RETURN_NONE;
    }
    const int64_t *values = (const int64_t *)view.buf;
    int64_t low = values[0], high = values[0];
    for (Py_ssize_t i = 1; i < count; i++) {
        low = values[i] < low ? values[i] : low;
        high = values[i] > high ? values[i] : high;
    }
    PyBuffer_Release(&view);
    return Py_BuildValue("(LL)", (long long)low, (long long)high);
}

static PyMethodDef methods[] = {
    {"weld", weld, METH_VARARGS, "weld(rows, corners) -> (first rows int64, corner indices int32)"},
    {"face_normals", face_normals, METH_VARARGS, "face_normals(points, triangles) -> float32 normals"},
    {"stl", stl, METH_VARARGS, "stl(data) -> (points float64, indices int32) of a binary STL, or None"},
    {"weld_take", weld_take, METH_VARARGS, "weld_take(rows, corners) -> (points float64, indices int32)"},
    {"columns", columns, METH_VARARGS, "columns(values, offset, stride, count, (c0, c1, c2)) -> float32 points"},
    {"place", place, METH_VARARGS, "place(points float32, matrix 3x4, unit) -> float64 points"},
    {"shift", shift, METH_VARARGS, "shift(int64 values, offset) -> int64 values"},
    {"bounds", bounds, METH_VARARGS, "bounds(int64 values) -> (min, max), or None when empty"},
    {"finish", finish, METH_VARARGS, "finish(points, triangles, scale, flip) -> (points, indices, normals, extent)"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_weld", "Mesh corner welding and face normals.", -1, methods,
};

PyMODINIT_FUNC PyInit__weld(void) { return PyModule_Create(&module); }
