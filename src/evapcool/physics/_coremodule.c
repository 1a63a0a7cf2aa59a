/*
 * evapcool.physics._core: the engine core (core/*.c, the same source the page compiles to
 * WebAssembly) bound to CPython. One `Core` object is one engine; physics/core.py's
 * CoreEngine drives it over a World. The arrays pass as buffers (NumPy arrays), read or
 * written in one pass in C: no Python object per atom.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "tables.h"

typedef struct {
  PyObject_HEAD Core *core;
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
  if (!self->core || !core_allocate(self->core, n, log_capacity)) {
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
  double *place = core->inputs;
  memcpy(place, in.buf, (size_t)in.len);
  memcpy(place + 7 * (Py_ssize_t)self->n, st.buf, (size_t)st.len);
  PyBuffer_Release(&in);
  PyBuffer_Release(&st);
  core_load(core, place, g, a, xl, xr, yb, knife, win_rule, record, time, won, pairs, walls);
  Py_RETURN_NONE;
}

/* start(energy_sum, trap_height): the grid, the cells and every prediction. */
static PyObject *core_py_start(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  double energy_sum, height;
  if (!core || !PyArg_ParseTuple(args, "dd", &energy_sum, &height)) return NULL;
  if (!core_start(core, energy_sum, height)) return PyErr_NoMemory();
  Py_RETURN_NONE;
}

/* advance_to(t_end) -> 0 when done, 1 when the log must be emptied first (take_log). */
static PyObject *core_py_advance_to(CoreObject *self, PyObject *arg) {
  Core *core = ready(self);
  if (!core) return NULL;
  double t_end = PyFloat_AsDouble(arg);
  if (t_end == -1.0 && PyErr_Occurred()) return NULL;
  int32_t status;
  Py_BEGIN_ALLOW_THREADS status = core_advance_to(core, t_end);
  Py_END_ALLOW_THREADS return PyLong_FromLong(status);
}

static PyObject *core_py_set_trap_height(CoreObject *self, PyObject *arg) {
  Core *core = ready(self);
  if (!core) return NULL;
  double h = PyFloat_AsDouble(arg);
  if (h == -1.0 && PyErr_Occurred()) return NULL;
  core_set_trap_height(core, h);
  Py_RETURN_NONE;
}

/* take_log() -> the log lines since the last take (bytes: int32 kind, a, b, pad; f64 t). */
static PyObject *core_py_take_log(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  PyObject *out = PyBytes_FromStringAndSize((const char *)core->event_log,
                                            (Py_ssize_t)core->run.n_log * sizeof(LogLine));
  core->run.n_log = 0;
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
  double *pos = v[0].buf, *vel = v[1].buf, *t = v[2].buf;
  int8_t *status = v[3].buf;
  int64_t *counter = v[4].buf;
  for (Py_ssize_t a = 0; a < n; a++) {
    int32_t r = core->row_of[a];
    const State *s = &core->state[r];
    pos[2 * a] = s->x;
    pos[2 * a + 1] = s->y;
    vel[2 * a] = s->vx;
    vel[2 * a + 1] = s->vy;
    t[a] = s->t;
    status[a] = (int8_t)core->plan[r].status;
    counter[a] = s->count;
  }
  for (int k = 0; k < 5; k++) PyBuffer_Release(&v[k]);
  Py_RETURN_NONE;
}

/* scalars() -> (time, energy_sum, won, n_trapped, pairs, walls, crossings, stale,
 * trap_height). */
static PyObject *core_py_scalars(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  const Run *r = &core->run;
  return Py_BuildValue("(ddOiLLLLd)", r->time, r->energy_sum, r->won ? Py_True : Py_False,
                       r->n_trapped, (long long)r->pairs, (long long)r->walls,
                       (long long)r->crossings, (long long)r->stale, r->trap_height);
}

static PyObject *core_py_force_win(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  core_force_win(core);
  Py_RETURN_NONE;
}

/* grid() -> (columns, rows, cell edge px, skin px). */
static PyObject *core_py_grid(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  return Py_BuildValue("(iidd)", core->run.nx, core->run.ny, core->run.cell, core->run.skin);
}

static PyObject *core_py_grid_errors(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  return PyLong_FromLong(core_grid_errors(core));
}


/* fill_tc_table(tc0, exponent): Tc(N) = Tc0 (N / N0)^p for N = 0..N0, the core's own power. */
static PyObject *core_py_fill_tc_table(CoreObject *self, PyObject *args) {
  Core *core = ready(self);
  double tc0, exponent;
  if (!core || !PyArg_ParseTuple(args, "dd", &tc0, &exponent)) return NULL;
  core_fill_tc_table(core, tc0, exponent);
  Py_RETURN_NONE;
}

/* frame(height) -> 0 when the whole frame is done, 1 when the log must be emptied first. */
static PyObject *core_py_frame(CoreObject *self, PyObject *arg) {
  Core *core = ready(self);
  if (!core) return NULL;
  double h = PyFloat_AsDouble(arg);
  if (h == -1.0 && PyErr_Occurred()) return NULL;
  int32_t status;
  Py_BEGIN_ALLOW_THREADS status = core_frame(core, h);
  Py_END_ALLOW_THREADS return PyLong_FromLong(status);
}

/* frame_end() -> True at the whole frame the win is first seen (the score fixed then). */
static PyObject *core_py_frame_end(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  return PyBool_FromLong(core_frame_end(core));
}

/* score() -> (atoms trapped at the end of the win's frame, that frame), or None before. */
static PyObject *core_py_score(CoreObject *self, PyObject *Py_UNUSED(ignored)) {
  Core *core = ready(self);
  if (!core) return NULL;
  if (core->run.score < 0) Py_RETURN_NONE;
  return Py_BuildValue("(id)", core->run.score, core->run.win_frame);
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

static PyMethodDef core_methods[] = {
    {"load", (PyCFunction)core_py_load, METH_VARARGS, "The atoms and the fixed parameters."},
    {"start", (PyCFunction)core_py_start, METH_VARARGS, "The grid and every prediction."},
    {"advance_to", (PyCFunction)core_py_advance_to, METH_O, "Events up to t_end: 0 done, 1 log full."},
    {"set_trap_height", (PyCFunction)core_py_set_trap_height, METH_O, "New rim height."},
    {"take_log", (PyCFunction)core_py_take_log, METH_NOARGS, "The log lines since the last take."},
    {"export", (PyCFunction)core_py_export, METH_VARARGS, "Stored states into the World's arrays."},
    {"scalars", (PyCFunction)core_py_scalars, METH_NOARGS, "The clock, sums and counts."},
    {"force_win", (PyCFunction)core_py_force_win, METH_NOARGS, "Latch the win."},
    {"grid", (PyCFunction)core_py_grid, METH_NOARGS, "(columns, rows, cell edge, skin)."},
    {"grid_errors", (PyCFunction)core_py_grid_errors, METH_NOARGS, "Atoms beyond their cell's skin."},
    {"fill_tc_table", (PyCFunction)core_py_fill_tc_table, METH_VARARGS, "Tc(N) for N = 0..n."},
    {"frame", (PyCFunction)core_py_frame, METH_O, "One whole frame, the height held: 0 done, 1 log full."},
    {"frame_end", (PyCFunction)core_py_frame_end, METH_NOARGS, "A whole frame's end: True if the win is seen."},
    {"score", (PyCFunction)core_py_score, METH_NOARGS, "(score, frame of the win) or None."},
    {"replay", (PyCFunction)core_py_replay, METH_VARARGS, "Frames played of (height, frames) runs."},
    {NULL, NULL, 0, NULL},
};

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

/* contraction_probe(a, b, c) -> a * b + c as the core computes it (two roundings). */
static PyObject *contraction_probe(PyObject *Py_UNUSED(module), PyObject *args) {
  double a, b, c;
  if (!PyArg_ParseTuple(args, "ddd", &a, &b, &c)) return NULL;
  return PyFloat_FromDouble(core_contraction_probe(a, b, c));
}


/* load_cup(pos, vel, radius, curvature, y_top, seed) -> atoms placed: the start from a seed
 * into pos and vel ((n, 2) float64 each); fewer than n if they do not fit, -1 for
 * impossible odds (core/start.c). */
static PyObject *load_cup(PyObject *Py_UNUSED(module), PyObject *args) {
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

/* cup_capacity(radius, curvature, y_top) -> atoms the loading places below y_top. */
static PyObject *cup_capacity(PyObject *Py_UNUSED(module), PyObject *args) {
  double radius, curvature, y_top;
  if (!PyArg_ParseTuple(args, "ddd", &radius, &curvature, &y_top)) return NULL;
  return PyLong_FromLong(core_cup_capacity(radius, curvature, y_top));
}

/* power(x, p) -> x^p from products and square roots (core/start.c). */
static PyObject *power(PyObject *Py_UNUSED(module), PyObject *args) {
  double x, p;
  if (!PyArg_ParseTuple(args, "dd", &x, &p)) return NULL;
  return PyFloat_FromDouble(core_power(x, p));
}

static PyMethodDef module_methods[] = {
    {"contraction_probe", contraction_probe, METH_VARARGS, "a * b + c, rounded twice."},
    {"load_cup", load_cup, METH_VARARGS, "The start from a seed into pos and vel."},
    {"cup_capacity", cup_capacity, METH_VARARGS, "Atoms the loading places below y_top."},
    {"power", power, METH_VARARGS, "x^p from products and square roots."},
    {NULL, NULL, 0, NULL},
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
  PyModule_AddIntConstant(m, "LOG_LINE_BYTES", (long)sizeof(LogLine));
#ifdef __VERSION__
  PyModule_AddStringConstant(m, "COMPILER", __VERSION__);
#else
  PyModule_AddStringConstant(m, "COMPILER", "unknown");
#endif
  return m;
}
