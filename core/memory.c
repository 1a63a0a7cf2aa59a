/*
 * Where an engine's tables live. In WebAssembly: a bump allocator over the instance's own
 * memory (the page makes one instance per engine and drops the instance, never a block).
 * Natively: zeroed, 64-byte aligned blocks from the C library, freed with the engine.
 */
#include "tables.h"

#ifdef __wasm__
extern unsigned char __heap_base;
static uintptr_t heap_top = (uintptr_t)&__heap_base;

/* n bytes on a 64-byte line, zeroed (fresh pages are); 0 if the memory cannot grow. */
static void *bump(uintptr_t bytes) {
  uintptr_t at = (heap_top + 63) & ~(uintptr_t)63;
  uintptr_t have = __builtin_wasm_memory_size(0) * 65536;
  if (bytes > 0xffffffffu - at) return 0;
  if (at + bytes > have) {
    uintptr_t pages = (at + bytes - have + 65535) / 65536;
    if (__builtin_wasm_memory_grow(0, pages) == (uintptr_t)-1) return 0;
  }
  heap_top = at + bytes;
  return (void *)at;
}

void *core_take(Core *core, uintptr_t bytes) {
  void *p = core->out_of_memory ? 0 : bump(bytes);
  if (!p) core->out_of_memory = 1;
  return p;
}

Core *core_new(void) { return bump(sizeof(Core)); }
void core_free(Core *core) { (void)core; }

#else
#include <stdlib.h>
#include <string.h>

void *core_take(Core *core, uintptr_t bytes) {
  if (core->out_of_memory || core->n_blocks == (int32_t)(sizeof core->blocks / sizeof(void *))) {
    core->out_of_memory = 1;
    return 0;
  }
  /* 64 bytes more than asked, to start on a line: the pointer freed is the block's own. */
  unsigned char *block = calloc(1, (size_t)bytes + 64);
  if (!block) {
    core->out_of_memory = 1;
    return 0;
  }
  core->blocks[core->n_blocks++] = block;
  return (void *)(((uintptr_t)block + 63) & ~(uintptr_t)63);
}

Core *core_new(void) { return calloc(1, sizeof(Core)); }

void core_free(Core *core) {
  if (!core) return;
  for (int32_t k = 0; k < core->n_blocks; k++) free(core->blocks[k]);
  free(core);
}
#endif
