/*
 * evapcool.physics._core: the engine core (core/*.c, the same source the page compiles to
 * WebAssembly) bound to CPython through its API alone (core/evapcool_core.h). One `Core`
 * object is one engine; physics/core.py's CoreEngine drives it over a World. The arrays pass
 * as buffers (NumPy arrays), read or written in one pass in C: no Python object per atom.
 * The method tables and the wrappers of plain numbers are generated from the header
 * (_core_glue.h, scripts/core_api.py); the wrappers of buffers and tuples are here.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <string.h>

#include "evapcool_core.h"

/* The hash of the core's sources this build was made from (setup.py; physics/coresource.py). */
#ifndef CORE_SOURCE_HASH
#define CORE_SOURCE_HASH "unknown"
#endif

typedef struct {
  PyObject_HEAD Core *core;
  double *inputs; /* where load() writes the atoms (core_allocate's answer) */
  int32_t n, log_capacity;
} CoreObject;

static void core_dealloc(CoreObject *self) {
  core_free(self->core);
  Py_TYPE(self)->tp_free((PyObject *)self);
}

/* Core(n_atoms, log_capacity): the tables of an engine of n atoms, allocated once. */
static int core_init(CoreObject *self, PyObject *args, PyObject *kwds) {
  static char *names[] = {"n_atoms", "log_capacity", NULL};
  int n, log_capacity;
  if (!PyArg_ParseTupleAndKeywords(args, kwds, "ii", names, &n, &log_capacity)) return -1;
  if (n < 1 || log_capacity < 1) {
    PyErr_SetString(PyExc_ValueError, "n_atoms and log_capacity must be at least 1");
    return -1;
  }
  if (self->core) return 0;
  self->core = core_new();
  self->inputs = self->core ? core_allocate(self->core, n, log_capacity) : NULL;
  if (!self->inputs) {
    PyErr_NoMemory();
    return -1;
  }
  self->n = n;
  self->log_capacity = log_capacity;
  return 0;
}

/* A C-contiguous buffer of `count` items of `size` bytes, or an exception. */
static int get_buffer(PyObject *obj, Py_buffer *view, Py_ssize_t count, Py_ssize_t size,
                      int writable, const char *what) {
  int flags = PyBUF_C_CONTIGUOUS | (writable ? PyBUF_WRITABLE : 0);
  if (PyObject_GetBuffer(obj, view, flags) < 0) return -1;
  if (view->len != count * size) {
    PyErr_Format(PyExc_ValueError, "%s: %zd bytes, expected %zd", what, view->len, count * size);
    PyBuffer_Release(view);
    return -1;
  }
  return 0;
}

static Core *ready(CoreObject *self) {
  if (!self->core) PyErr_SetString(PyExc_RuntimeError, "the core was not set up");
  return self->core;
}

/*
 * load(inputs, status, gravity, curvature, x_left, x_right, y_bottom, knife, win_rule,
 * record, time, won, pairs, walls): the atoms (inputs: x, y, vx, vy, t, radius, mass, n
 * float64 each; status: n int32) and the fixed parameters.
 */
static PyObject *core_py_load(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  if (!core) return NULL;
  PyObject *inputs, *status;
  double g, a, xl, xr, yb, time, pairs, walls;
  int knife, win_rule, record, won;
  if (!PyArg_ParseTuple(args, "OOdddddpppdpdd", &inputs, &status, &g, &a, &xl, &xr, &yb,
                        &knife, &win_rule, &record, &time, &won, &pairs, &walls))
    return NULL;
  Py_buffer in, st;
  if (get_buffer(inputs, &in, 7 * (Py_ssize_t)self->n, 8, 0, "inputs") < 0) return NULL;
  if (get_buffer(status, &st, self->n, 4, 0, "status") < 0) {
    PyBuffer_Release(&in);
    return NULL;
  }
  double *place = self->inputs;
  memcpy(place, in.buf, (size_t)in.len);
  memcpy(place + 7 * (Py_ssize_t)self->n, st.buf, (size_t)st.len);
  PyBuffer_Release(&in);
  PyBuffer_Release(&st);
  core_load(core, place, g, a, xl, xr, yb, knife, win_rule, record, time, won, pairs, walls);
  Py_RETURN_NONE;
}

/* take_log() -> the log lines since the last take (bytes: int32 kind, a, b, pad; f64 t). */
static PyObject *core_py_take_log(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  PyObject *out = PyBytes_FromStringAndSize((const char *)core_log_address(core),
                                            (Py_ssize_t)core_n_log(core) * sizeof(LogLine));
  core_log_clear(core);
  return out;
}

/* export(pos, vel, t_atom, status, counter): every atom's stored state, by World index,
 * into the World's arrays ((n, 2) f64, (n, 2) f64, n f64, n int8, n int64). */
static PyObject *core_py_export(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  PyObject *objs[5];
  if (!core || !PyArg_ParseTuple(args, "OOOOO", &objs[0], &objs[1], &objs[2], &objs[3], &objs[4]))
    return NULL;
  const Py_ssize_t n = self->n, counts[5] = {2 * n, 2 * n, n, n, n}, sizes[5] = {8, 8, 8, 1, 8};
  static const char *what[5] = {"pos", "vel", "t_atom", "status", "counter"};
  Py_buffer v[5];
  for (int k = 0; k < 5; k++)
    if (get_buffer(objs[k], &v[k], counts[k], sizes[k], 1, what[k]) < 0) {
      while (k--) PyBuffer_Release(&v[k]);
      return NULL;
    }
  core_export_states(core, v[0].buf, v[1].buf, v[2].buf, v[3].buf, v[4].buf);
  for (int k = 0; k < 5; k++) PyBuffer_Release(&v[k]);
  Py_RETURN_NONE;
}

/* scalars() -> (time, energy_sum, won, n_trapped, pairs, walls, crossings, stale,
 * trap_height). */
static PyObject *core_py_scalars(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  return Py_BuildValue("(ddOiLLLLd)", core_time(core), core_energy_sum(core),
                       core_won(core) ? Py_True : Py_False, core_n_trapped(core),
                       (long long)core_pairs(core), (long long)core_walls(core),
                       (long long)core_crossings(core), (long long)core_stale(core),
                       core_trap_height(core));
}

/* grid() -> (columns, rows, cell edge px, skin px). */
static PyObject *core_py_grid(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  return Py_BuildValue("(iidd)", core_nx(core), core_ny(core), core_cell(core), core_skin(core));
}

/* score() -> (atoms trapped at the end of the win's frame, that frame), or None before. */
static PyObject *core_py_score(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  if (core_score(core) < 0) Py_RETURN_NONE;
  return Py_BuildValue("(id)", core_score(core), core_win_frame(core));
}

/* replay(runs, limit) -> frames played: runs float64 (height, frames) pairs. */
static PyObject *core_py_replay(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  PyObject *runs;
  int limit;
  if (!core || !PyArg_ParseTuple(args, "Oi", &runs, &limit)) return NULL;
  Py_buffer view;
  if (PyObject_GetBuffer(runs, &view, PyBUF_C_CONTIGUOUS) < 0) return NULL;
  if (view.len % 16 != 0) {
    PyBuffer_Release(&view);
    PyErr_SetString(PyExc_ValueError, "runs: float64 (height, frames) pairs");
    return NULL;
  }
  int32_t frames;
  Py_BEGIN_ALLOW_THREADS frames = core_replay(core, view.buf, (int32_t)(view.len / 16), limit);
  Py_END_ALLOW_THREADS PyBuffer_Release(&view);
  return PyLong_FromLong(frames);
}

/* path(runs, limit, stride, h0) -> (frames played, the points' rows (k, N, T, h) as bytes of
 * float64): runs float64 (height, frames) pairs. */
static PyObject *core_py_path(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  PyObject *runs;
  int limit, stride;
  double h0;
  if (!core || !PyArg_ParseTuple(args, "Oiid", &runs, &limit, &stride, &h0)) return NULL;
  if (limit < 0 || stride < 1) {
    PyErr_SetString(PyExc_ValueError, "limit must be at least 0 and stride at least 1");
    return NULL;
  }
  Py_buffer view;
  if (PyObject_GetBuffer(runs, &view, PyBUF_C_CONTIGUOUS) < 0) return NULL;
  if (view.len % 16 != 0) {
    PyBuffer_Release(&view);
    PyErr_SetString(PyExc_ValueError, "runs: float64 (height, frames) pairs");
    return NULL;
  }
  Py_ssize_t rows = limit / stride + 2;
  double *points = PyMem_Malloc(sizeof(double) * 4 * rows);
  if (!points) {
    PyBuffer_Release(&view);
    return PyErr_NoMemory();
  }
  int32_t frames, kept = 0;
  Py_BEGIN_ALLOW_THREADS
  frames = core_path(core, view.buf, (int32_t)(view.len / 16), limit, stride, h0, points, &kept);
  Py_END_ALLOW_THREADS
  PyBuffer_Release(&view);
  PyObject *out = Py_BuildValue("(iy#)", frames, (const char *)points, (Py_ssize_t)kept * 32);
  PyMem_Free(points);
  return out;
}

/* load_cup(pos, vel, radius, curvature, y_top, seed) -> atoms placed: the start from a seed
 * into pos and vel ((n, 2) float64 each); fewer than n if they do not fit, -1 for
 * impossible odds (core/start.c). */
static PyObject *py_load_cup(PyObject *Py_UNUSED(module), PyObject *args) {
  PyObject *objs[2];
  double radius, curvature, y_top;
  unsigned long long seed;
  if (!PyArg_ParseTuple(args, "OOdddK", &objs[0], &objs[1], &radius, &curvature, &y_top, &seed))
    return NULL;
  Py_buffer v[2];
  if (PyObject_GetBuffer(objs[0], &v[0], PyBUF_C_CONTIGUOUS | PyBUF_WRITABLE) < 0) return NULL;
  Py_ssize_t n = v[0].len / 16;
  if (get_buffer(objs[1], &v[1], 2 * n, 8, 1, "vel") < 0) {
    PyBuffer_Release(&v[0]);
    return NULL;
  }
  int32_t placed = n < 1 ? 0 : core_load_cup(v[0].buf, v[1].buf, (int32_t)n, radius, curvature, y_top,
                                             (uint32_t)seed, (uint32_t)(seed >> 32));
  PyBuffer_Release(&v[0]);
  PyBuffer_Release(&v[1]);
  return PyLong_FromLong(placed);
}

/* first_overlap(x, y, radius, include, tol) -> (i, j) or None: the first overlapping pair of
 * included atoms (x, y, radius n float64 each, include n int8 or bool; core/overlap.c). */
static PyObject *py_first_overlap(PyObject *Py_UNUSED(module), PyObject *args) {
  PyObject *objs[4];
  double tol;
  if (!PyArg_ParseTuple(args, "OOOOd", &objs[0], &objs[1], &objs[2], &objs[3], &tol)) return NULL;
  Py_buffer v[4];
  static const char *what[] = {"x", "y", "radius", "include"};
  if (PyObject_GetBuffer(objs[0], &v[0], PyBUF_C_CONTIGUOUS) < 0) return NULL;
  Py_ssize_t n = v[0].len / 8, got = 1;
  for (; got < 4; got++)
    if (get_buffer(objs[got], &v[got], n, got < 3 ? 8 : 1, 0, what[got]) < 0) break;
  int32_t *work = got == 4 && n < INT32_MAX / 8 ? PyMem_Malloc(sizeof(int32_t) * (6 * n + 2)) : NULL;
  int32_t pair[2], found = 0;
  if (work) {
    Py_BEGIN_ALLOW_THREADS
    found = core_first_overlap(v[0].buf, v[1].buf, v[2].buf, v[3].buf, (int32_t)n, tol, work, pair);
    Py_END_ALLOW_THREADS
    PyMem_Free(work);
  }
  for (Py_ssize_t k = 0; k < got; k++) PyBuffer_Release(&v[k]);
  if (got < 4) return NULL;
  if (!work) return PyErr_NoMemory();
  if (!found) Py_RETURN_NONE;
  return Py_BuildValue("(ii)", pair[0], pair[1]);
}

#include "_core_glue.h"

static PyTypeObject CoreType = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "evapcool.physics._core.Core",
    .tp_basicsize = sizeof(CoreObject),
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "One engine of the core: its scalars and tables.",
    .tp_new = PyType_GenericNew,
    .tp_init = (initproc)core_init,
    .tp_dealloc = (destructor)core_dealloc,
    .tp_methods = core_methods,
};

static struct PyModuleDef core_module = {
    PyModuleDef_HEAD_INIT, "evapcool.physics._core",
    "The engine core (core/*.c) bound to CPython.", -1, module_methods,
};

PyMODINIT_FUNC PyInit__core(void) {
  if (PyType_Ready(&CoreType) < 0) return NULL;
  PyObject *m = PyModule_Create(&core_module);
  if (!m) return NULL;
  Py_INCREF(&CoreType);
  if (PyModule_AddObject(m, "Core", (PyObject *)&CoreType) < 0) {
    Py_DECREF(&CoreType);
    Py_DECREF(m);
    return NULL;
  }
  PyModule_AddStringConstant(m, "SOURCE_HASH", CORE_SOURCE_HASH);
#ifdef __VERSION__
  PyModule_AddStringConstant(m, "COMPILER", __VERSION__);
#else
  PyModule_AddStringConstant(m, "COMPILER", "unknown");
#endif
  return m;
}
