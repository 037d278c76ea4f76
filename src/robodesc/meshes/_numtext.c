/* Whitespace-separated numbers in text, parsed to packed float64 or int64.
 *
 * Mesh files (COLLADA float_array and <p>, OBJ) are mostly numbers in text, and parsing them was
 * the largest single cost of converting a mesh-heavy robot: numpy.fromstring(sep=" ") spends about
 * 200 ns per float on a 7-to-10-digit mesh number, this about 30 ns. The doubles are the ones a
 * correctly rounded parser gives, bit for bit: short decimals take Clinger's exact fast path, all
 * others PyOS_string_to_double (the parser behind float() and numpy.fromstring). Nothing here
 * imports numpy: the result is a bytearray the caller views with frombuffer.
 *
 * parse(text: str | bytes, integers: bool) -> bytearray
 *     Raises ValueError("bad token at N") with N the token's index when a token is not a number
 *     (or an integer that does not fit int64). Separators are the C locale's isspace characters,
 *     as numpy.fromstring(sep=" ") takes them.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <stdint.h>
#include <string.h>

static int is_space(char c) {
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

/* One decimal integer token [+-]?[0-9]+, exactly; 0 on success. */
static int parse_int(const char *s, const char *end, int64_t *out) {
    int negative = 0;
    if (s < end && (*s == '+' || *s == '-')) {
        negative = *s == '-';
        s++;
    }
    if (s == end) {
        return -1;
    }
    /* Accumulate as a negative number so INT64_MIN fits. */
    int64_t value = 0;
    for (; s < end; s++) {
        if (*s < '0' || *s > '9') {
            return -1;
        }
        int digit = *s - '0';
        if (value < (INT64_MIN + digit) / 10) {
            return -1;
        }
        value = value * 10 - digit;
    }
    if (!negative) {
        if (value == INT64_MIN) {
            return -1;
        }
        value = -value;
    }
    *out = value;
    return 0;
}

/* Powers of ten that are exact doubles (5^22 < 2^53). */
static const double exact_powers[] = {
    1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
    1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
};

/* Clinger's fast path: a decimal [+-]?digits[.digits][(e|E)[+-]?digits] whose digits make an
 * integer m <= 2^53 and whose power of ten e has |e| <= 22 is m * 10^e or m / 10^-e, one correctly
 * rounded IEEE operation on two exact doubles, so the same double a correctly rounded parser gives.
 * Mesh numbers (7 to 10 digits) nearly all qualify; 1 when the token is not such a number. */
static int parse_simple(const char *s, const char *end, double *out) {
#if FLT_EVAL_METHOD != 0
    /* Wider intermediates (x87) would round twice: leave every token to the exact parser. */
    return 1;
#endif
    int negative = 0;
    if (*s == '+' || *s == '-') {
        negative = *s == '-';
        s++;
    }
    uint64_t mantissa = 0;
    int digits = 0;      /* significant digits in mantissa (leading zeros skipped) */
    int any = 0;         /* whether the mantissa had a digit at all */
    int scale = 0;       /* digits after the point */
    for (; s < end && *s >= '0' && *s <= '9'; s++) {
        any = 1;
        if (mantissa == 0 && *s == '0') {
            continue;
        }
        if (++digits > 19) {
            return 1;
        }
        mantissa = mantissa * 10 + (uint64_t)(*s - '0');
    }
    if (s < end && *s == '.') {
        for (s++; s < end && *s >= '0' && *s <= '9'; s++) {
            any = 1;
            scale++;
            if (mantissa == 0 && *s == '0') {
                continue;
            }
            if (++digits > 19) {
                return 1;
            }
            mantissa = mantissa * 10 + (uint64_t)(*s - '0');
        }
    }
    if (!any) {
        return 1;
    }
    int exponent = 0;
    if (s < end && (*s == 'e' || *s == 'E')) {
        s++;
        int exponent_negative = 0;
        if (s < end && (*s == '+' || *s == '-')) {
            exponent_negative = *s == '-';
            s++;
        }
        if (s == end) {
            return 1;
        }
        for (; s < end && *s >= '0' && *s <= '9'; s++) {
            if (exponent > 1000) {
                return 1;
            }
            exponent = exponent * 10 + (*s - '0');
        }
        if (exponent_negative) {
            exponent = -exponent;
        }
    }
    if (s != end || mantissa > ((uint64_t)1 << 53)) {
        return 1;
    }
    int power = exponent - scale;
    double value = (double)mantissa;
    if (power < 0) {
        if (power < -22) {
            return 1;
        }
        value = value / exact_powers[-power];
    } else {
        if (power > 22) {
            return 1;
        }
        value = value * exact_powers[power];
    }
    *out = negative ? -value : value;
    return 0;
}

/* One float token as float() reads it (without underscores): the fast path, else
 * PyOS_string_to_double, the parser behind float() and numpy.fromstring; 0 on success. The token is
 * followed by a separator or the buffer's terminating NUL, so that parser stops at its end. */
static int parse_double(const char *s, const char *end, double *out) {
    if (parse_simple(s, end, out) == 0) {
        return 0;
    }
    char *stop = NULL;
    double value = PyOS_string_to_double(s, &stop, NULL);
    if (value == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        return -1;
    }
    if (stop != end) {
        return -1;
    }
    if (value != value) {
        /* numpy reads "-nan" as the positive quiet NaN, as it reads "nan". */
        uint64_t bits = 0x7ff8000000000000ULL;
        memcpy(&value, &bits, 8);
    }
    *out = value;
    return 0;
}

static PyObject *parse(PyObject *self, PyObject *args) {
    PyObject *text;
    int integers;
    if (!PyArg_ParseTuple(args, "Op", &text, &integers)) {
        return NULL;
    }
    const char *data;
    Py_ssize_t size;
    if (PyUnicode_Check(text)) {
        data = PyUnicode_AsUTF8AndSize(text, &size);
        if (data == NULL) {
            return NULL;
        }
    } else if (PyBytes_Check(text)) {
        data = PyBytes_AS_STRING(text);
        size = PyBytes_GET_SIZE(text);
    } else {
        PyErr_SetString(PyExc_TypeError, "parse() takes str or bytes");
        return NULL;
    }
    /* At most one number per two bytes ("1 1 1"), plus one for text without a trailing separator. */
    Py_ssize_t capacity = size / 2 + 1;
    PyObject *out = PyByteArray_FromStringAndSize(NULL, capacity * 8);
    if (out == NULL) {
        return NULL;
    }
    char *cursor = PyByteArray_AS_STRING(out);
    const char *p = data;
    const char *end = data + size;
    Py_ssize_t count = 0;
    int bad = 0;
    while (1) {
        while (p < end && is_space(*p)) {
            p++;
        }
        if (p == end) {
            break;
        }
        const char *start = p;
        while (p < end && !is_space(*p)) {
            p++;
        }
        if (integers) {
            int64_t value;
            if (parse_int(start, p, &value) != 0) {
                bad = 1;
                break;
            }
            memcpy(cursor, &value, 8);
        } else {
            double value;
            if (parse_double(start, p, &value) != 0) {
                bad = 1;
                break;
            }
            memcpy(cursor, &value, 8);
        }
        cursor += 8;
        count++;
    }
    if (bad) {
        Py_DECREF(out);
        PyErr_Format(PyExc_ValueError, "bad token at %zd", count);
        return NULL;
    }
    if (PyByteArray_Resize(out, count * 8) != 0) {
        Py_DECREF(out);
        return NULL;
    }
    return out;
}


/* The space- or tab-separated tokens of one line, from ``p`` up to ``end``: the next token's bounds
 * in (*start, *stop); 0 when there is none left. */
static int next_token(const char **p, const char *end, const char **start, const char **stop) {
    const char *q = *p;
    while (q < end && (*q == ' ' || *q == '\t')) {
        q++;
    }
    if (q == end) {
        *p = q;
        return 0;
    }
    *start = q;
    while (q < end && *q != ' ' && *q != '\t') {
        q++;
    }
    *stop = q;
    *p = q;
    return 1;
}

/* Growable packed buffer for obj(). */
typedef struct {
    char *data;
    Py_ssize_t size, capacity;
} Packed;

static int packed_add(Packed *b, const void *value, Py_ssize_t width) {
    if (b->size + width > b->capacity) {
        Py_ssize_t capacity = b->capacity ? 2 * b->capacity : 4096;
        while (capacity < b->size + width) {
            capacity *= 2;
        }
        char *grown = PyMem_Realloc(b->data, capacity);
        if (grown == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        b->data = grown;
        b->capacity = capacity;
    }
    memcpy(b->data + b->size, value, width);
    b->size += width;
    return 0;
}

/* The vertices and fan-triangulated faces of a Wavefront OBJ text whose line breaks are all "\n"
 * and whose bytes are printable ASCII, tabs and breaks on ``v``/``f`` lines (the caller checks the
 * rest). It reads what usd_meshio's line reader reads, the same way: lines starting "v " give x, y,
 * z (the first three tokens after the keyword; more are ignored), lines starting "f " give corners
 * (each token up to its first "/", an index from 1) fanned into triangles (v0, vk, vk+1). Returns
 * (vertices float64, triangles int32) or None whenever that reader must decide: a short or bad
 * vertex line, a bad or relative (negative) index, an index past the vertices, a non-ASCII byte
 * on such a line. */
static PyObject *obj(PyObject *self, PyObject *args) {
    PyObject *text;
    /* bytes, whose terminating NUL stops PyOS_string_to_double after the last token. */
    if (!PyArg_ParseTuple(args, "S", &text)) {
        return NULL;
    }
    const char *p = PyBytes_AS_STRING(text);
    const char *end = p + PyBytes_GET_SIZE(text);
    Packed vertices = {NULL, 0, 0}, triangles = {NULL, 0, 0};
    PyObject *result = NULL;
    int64_t largest = 0;
    int fallback = 0;
    while (p < end && !fallback) {
        const char *line_end = memchr(p, '\n', end - p);
        if (line_end == NULL) {
            line_end = end;
        }
        int vertex = line_end - p >= 2 && p[0] == 'v' && p[1] == ' ';
        int face = line_end - p >= 2 && p[0] == 'f' && p[1] == ' ';
        if (vertex || face) {
            for (const char *c = p; c < line_end; c++) {
                if ((unsigned char)*c > 126) {
                    fallback = 1;
                }
            }
        }
        const char *q = p + 2, *start, *stop;
        if (vertex && !fallback) {
            for (int j = 0; j < 3; j++) {
                double value;
                /* A token ends at a space, a tab or the line's end: the parsers stop there. */
                if (!next_token(&q, line_end, &start, &stop) || parse_double(start, stop, &value) != 0) {
                    fallback = 1;
                    break;
                }
                if (packed_add(&vertices, &value, 8) != 0) {
                    goto done;
                }
            }
        } else if (face && !fallback) {
            int32_t first = 0, previous = 0;
            int corner = 0;
            while (next_token(&q, line_end, &start, &stop)) {
                const char *slash = memchr(start, '/', stop - start);
                int64_t index;
                if (parse_int(start, slash ? slash : stop, &index) != 0 || index <= 0 || index > INT32_MAX) {
                    fallback = 1;
                    break;
                }
                largest = index > largest ? index : largest;
                int32_t point = (int32_t)(index - 1);
                if (corner == 0) {
                    first = point;
                } else if (corner >= 2) {
                    int32_t triangle[3] = {first, previous, point};
                    if (packed_add(&triangles, triangle, 12) != 0) {
                        goto done;
                    }
                }
                previous = point;
                corner++;
            }
        }
        p = line_end + 1;
    }
    if (fallback || largest > vertices.size / 24) {
        result = Py_NewRef(Py_None);
        goto done;
    }
    PyObject *v = PyByteArray_FromStringAndSize(vertices.data ? vertices.data : "", vertices.size);
    PyObject *t = PyByteArray_FromStringAndSize(triangles.data ? triangles.data : "", triangles.size);
    if (v != NULL && t != NULL) {
        result = PyTuple_Pack(2, v, t);
    }
    Py_XDECREF(v);
    Py_XDECREF(t);
done:
    PyMem_Free(vertices.data);
    PyMem_Free(triangles.data);
    return result;
}

static PyMethodDef methods[] = {
    {"parse", parse, METH_VARARGS, "parse(text, integers) -> bytearray of packed float64 or int64"},
    {"obj", obj, METH_VARARGS, "obj(data) -> (vertices float64, triangles int32) of an OBJ text, or None"},
    {NULL, NULL, 0, NULL},
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_numtext", "Whitespace-separated numbers in text, parsed fast.", -1, methods,
};

PyMODINIT_FUNC PyInit__numtext(void) { return PyModule_Create(&module); }
