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
    const uint64_t *rows = (const uint64_t *)rows_view.buf;
    Py_ssize_t row_count = rows_view.len / 24;
    const int64_t *corners = have_corners ? (const int64_t *)corners_view.buf : NULL;
    Py_ssize_t count = have_corners ? corners_view.len / 8 : row_count;
    PyObject *result = NULL, *first = NULL, *indices = NULL;
    int32_t *table = NULL;

    if (count > INT32_MAX) {
        PyErr_SetString(PyExc_ValueError, "too many corners for 32-bit indices");
        goto done;
    }
    /* Open addressing at a load factor of at most one half; slots hold point numbers, -1 empty. */
    Py_ssize_t capacity = 16;
    while (capacity < 2 * count) {
        capacity *= 2;
    }
    uint64_t mask = (uint64_t)capacity - 1;
    table = PyMem_Malloc(capacity * sizeof(int32_t));
    first = PyByteArray_FromStringAndSize(NULL, count * 8);
    indices = PyByteArray_FromStringAndSize(NULL, count * 4);
    if (table == NULL || first == NULL || indices == NULL) {
        if (table == NULL) {
            PyErr_NoMemory();
        }
        goto done;
    }
    memset(table, 0xff, capacity * sizeof(int32_t));
    int64_t *first_rows = (int64_t *)PyByteArray_AS_STRING(first);
    int32_t *out = (int32_t *)PyByteArray_AS_STRING(indices);
    int32_t points = 0;
    for (Py_ssize_t k = 0; k < count; k++) {
        int64_t r = have_corners ? corners[k] : (int64_t)k;
        if (r < 0 || r >= row_count) {
            PyErr_Format(PyExc_ValueError, "corner %zd refers to row %lld of %zd", k, (long long)r, row_count);
            goto done;
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
    if (PyByteArray_Resize(first, (Py_ssize_t)points * 8) != 0) {
        goto done;
    }
    result = PyTuple_Pack(2, first, indices);
done:
    PyMem_Free(table);
    Py_XDECREF(first);
    Py_XDECREF(indices);
    PyBuffer_Release(&rows_view);
    if (have_corners) {
        PyBuffer_Release(&corners_view);
    }
    return result;
}

static PyObject *face_normals(PyObject *self, PyObject *args) {
    PyObject *points_object, *triangles_object;
    if (!PyArg_ParseTuple(args, "OO", &points_object, &triangles_object)) {
        return NULL;
    }
    Py_buffer points_view, triangles_view;
    if (get_buffer(points_object, &points_view, "points") != 0) {
        return NULL;
    }
    if (PyObject_GetBuffer(triangles_object, &triangles_view, PyBUF_C_CONTIGUOUS) != 0) {
        PyBuffer_Release(&points_view);
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
            const double *a = p + 3 * i0, *b = p + 3 * i1, *c = p + 3 * i2;
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
                normal[3 * t + j] = (float)(v + 0.0);
            }
        }
    }
    PyBuffer_Release(&points_view);
    PyBuffer_Release(&triangles_view);
    return out;
}

static PyMethodDef methods[] = {
    {"weld", weld, METH_VARARGS, "weld(rows, corners) -> (first rows int64, corner indices int32)"},
    {"face_normals", face_normals, METH_VARARGS, "face_normals(points, triangles) -> float32 normals"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_meshweld", "Mesh corner welding and face normals.", -1, methods,
};

PyMODINIT_FUNC PyInit__meshweld(void) { return PyModule_Create(&module); }
