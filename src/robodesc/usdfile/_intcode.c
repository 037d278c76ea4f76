/* Sdf's integer coding (integerCoding.cpp) of 32-bit integers, for .usdc int arrays and sections.
 *
 * The Python version in usdc_encoding.encode_ints is the reference; this one gives the same bytes
 * (tests/usdfile/test_usdc_intcode.py) for the millions of mesh indices a robot's geometry layer holds,
 * where the Python loop would take seconds.
 *
 * Output: int32 most common delta, 2-bit codes (four per byte, low bits first), then each delta that
 * is not the common one as int8, int16 or int32 (codes 1, 2, 3), little-endian.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <stdint.h>
#include <string.h>

/* Most common value of ``deltas`` (ties: the largest). A long list's deltas (mesh indices) are
 * mostly small: those are counted in a direct table that stays in cache, the rest in an
 * open-addressing table sized to them alone. A short list goes to that table whole. */
#define NEAR 32768
#define DIRECT_FROM 65536 /* below this many values, clearing the direct table costs more than it saves */

static void consider(int32_t value, Py_ssize_t seen, int32_t *best, Py_ssize_t *best_count) {
    if (seen > *best_count || (seen == *best_count && value > *best)) {
        *best = value;
        *best_count = seen;
    }
}

static int most_common(const int32_t *deltas, Py_ssize_t count, int32_t *common) {
    int32_t best = 0;
    Py_ssize_t best_count = 0;
    int32_t near_low = 0, near_high = 0; /* [low, high): the direct table's range, empty for a short list */
    Py_ssize_t far = count;
    if (count >= DIRECT_FROM) {
        near_low = -NEAR, near_high = NEAR;
        uint32_t *near = PyMem_Calloc(2 * NEAR, sizeof(uint32_t));
        if (near == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        far = 0;
        for (Py_ssize_t i = 0; i < count; i++) {
            int32_t d = deltas[i];
            if (d >= -NEAR && d < NEAR) {
                near[d + NEAR]++;
            } else {
                far++;
            }
        }
        for (int32_t d = -NEAR; d < NEAR; d++) {
            if (near[d + NEAR]) {
                consider(d, (Py_ssize_t)near[d + NEAR], &best, &best_count);
            }
        }
        PyMem_Free(near);
    }
    if (far > 0) {
        size_t size = 16;
        while (size < (size_t)far * 2) {
            size <<= 1;
        }
        int32_t *keys = PyMem_Malloc(size * sizeof(int32_t));
        Py_ssize_t *counts = PyMem_Calloc(size, sizeof(Py_ssize_t));
        if (keys == NULL || counts == NULL) {
            PyMem_Free(keys);
            PyMem_Free(counts);
            PyErr_NoMemory();
            return -1;
        }
        for (Py_ssize_t i = 0; i < count; i++) {
            int32_t d = deltas[i];
            if (d >= near_low && d < near_high) {
                continue;
            }
            size_t slot = (size_t)(((uint32_t)d * 2654435761u) & (size - 1));
            while (counts[slot] != 0 && keys[slot] != d) {
                slot = (slot + 1) & (size - 1);
            }
            keys[slot] = d;
            consider(d, ++counts[slot], &best, &best_count);
        }
        PyMem_Free(keys);
        PyMem_Free(counts);
    }
    *common = best;
    return 0;
}

static void put_le(unsigned char *out, uint32_t value, int bytes) {
    for (int k = 0; k < bytes; k++) {
        out[k] = (unsigned char)(value >> (8 * k));
    }
}

static PyObject *encode(PyObject *self, PyObject *args) {
    Py_buffer view;
    if (!PyArg_ParseTuple(args, "y*", &view)) {
        return NULL;
    }
    if (view.len % 4) {
        PyBuffer_Release(&view);
        PyErr_SetString(PyExc_ValueError, "expected whole int32 values");
        return NULL;
    }
    Py_ssize_t count = view.len / 4;
    if (count == 0) {
        PyBuffer_Release(&view);
        return PyBytes_FromStringAndSize(NULL, 0);
    }
    int32_t *deltas = PyMem_Malloc((size_t)count * sizeof(int32_t));
    if (deltas == NULL) {
        PyBuffer_Release(&view);
        return PyErr_NoMemory();
    }
    const unsigned char *raw = view.buf;
    uint32_t previous = 0;
    for (Py_ssize_t i = 0; i < count; i++) {
        const unsigned char *at = raw + 4 * i; /* little-endian, as the file stores them */
        uint32_t value = (uint32_t)at[0] | (uint32_t)at[1] << 8 | (uint32_t)at[2] << 16 | (uint32_t)at[3] << 24;
        deltas[i] = (int32_t)(value - previous); /* int32 arithmetic, wrapping, as the C++ coder */
        previous = value;
    }
    PyBuffer_Release(&view);
    int32_t common;
    if (most_common(deltas, count, &common) != 0) {
        PyMem_Free(deltas);
        return NULL;
    }
    Py_ssize_t code_bytes = (count * 2 + 7) / 8;
    /* Room for every delta at four bytes (and one more, so that each can be stored whole): the
     * bytes object is cut to what was used at the end. */
    PyObject *out = PyBytes_FromStringAndSize(NULL, 4 + code_bytes + 4 * count + 4);
    if (out == NULL) {
        PyMem_Free(deltas);
        return NULL;
    }
    unsigned char *buf = (unsigned char *)PyBytes_AS_STRING(out);
    put_le(buf, (uint32_t)common, 4);
    unsigned char *codes = buf + 4;
    unsigned char *data = codes + code_bytes;
    static const int widths[4] = {0, 1, 2, 4};
    memset(codes, 0, (size_t)code_bytes);
    for (Py_ssize_t i = 0; i < count; i++) {
        int32_t d = deltas[i];
        uint32_t u = (uint32_t)d;
        /* 0 the common delta, else 1 + (beyond int8) + (beyond int16): no branch to mispredict */
        int code = (d != common) * (1 + ((u + 0x80u) > 0xFFu) + ((u + 0x8000u) > 0xFFFFu));
        put_le(data, u, 4);
        data += widths[code];
        codes[i >> 2] |= (unsigned char)(code << (2 * (i & 3)));
    }
    if (_PyBytes_Resize(&out, data - buf) != 0) {
        PyMem_Free(deltas);
        return NULL;
    }
    PyMem_Free(deltas);
    return out;
}

static PyMethodDef methods[] = {
    {"encode", encode, METH_VARARGS, "encode(little-endian int32 bytes) -> bytes of Sdf's integer coding"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_intcode", "Sdf's integer coding of int32 values.", -1, methods,
};

PyMODINIT_FUNC PyInit__intcode(void) { return PyModule_Create(&module); }
