/* stiffpath_ini.h: the [STIFFPATH] settings of the machine's INI file, for modules loaded without parameters.
 *
 * The `linuxcnc` script exports INI_FILE_NAME before it starts the real-time environment, so a module
 * loaded by `loadrt [KINS]KINEMATICS` can read [STIFFPATH]ROBOT itself: the INI then names the robot
 * once. A relative path is taken relative to the INI file's folder, as LinuxCNC does for its own
 * files. Called at load time only (it reads a file), never in a real-time function. */
#ifndef STIFFPATH_INI_H
#define STIFFPATH_INI_H

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Copies the value of `key` in `[section]` of the INI file `path` into out (NUL-terminated, trimmed).
 * Returns 0 when found, -1 when the file cannot be read or the key is absent, -2 when the value does
 * not fit into out. Lines: "[SECTION]", "KEY = VALUE", comments starting with # or ;. */
static int stiffpath_ini_get(const char *path, const char *section, const char *key, char *out, size_t size) {
  FILE *file = fopen(path, "r");
  if (!file) return -1;
  char line[1024];
  int in_section = 0, result = -1;
  const size_t key_length = strlen(key), section_length = strlen(section);
  while (fgets(line, sizeof line, file)) {
    char *p = line;
    while (isspace((unsigned char)*p)) ++p;
    if (*p == '#' || *p == ';' || *p == '\0') continue;
    if (*p == '[') {
      in_section = strncmp(p + 1, section, section_length) == 0 && p[1 + section_length] == ']';
      continue;
    }
    if (!in_section || strncmp(p, key, key_length) != 0) continue;
    p += key_length;
    while (*p == ' ' || *p == '\t') ++p;
    if (*p != '=') continue;
    ++p;
    while (*p == ' ' || *p == '\t') ++p;
    size_t n = strlen(p);
    while (n > 0 && isspace((unsigned char)p[n - 1])) --n;
    if (n + 1 > size) {
      result = -2;
      break;
    }
    memcpy(out, p, n);
    out[n] = '\0';
    result = 0;
    break;
  }
  fclose(file);
  return result;
}

/* [STIFFPATH]<key> of the INI named by INI_FILE_NAME. A relative path is taken relative to the INI's folder
 * when it names a file there or contains a '/'; otherwise (a preset or built-in name) it is kept. Returns 0,
 * or -1 with a reason in `why`. */
static int stiffpath_ini_setting(const char *key, char *out, size_t size, const char **why) {
  const char *ini = getenv("INI_FILE_NAME");
  char value[768];
  if (!ini || !*ini) {
    *why = "no INI file (INI_FILE_NAME is not set: not started by the linuxcnc script)";
    return -1;
  }
  const int found = stiffpath_ini_get(ini, "STIFFPATH", key, value, sizeof value);
  if (found == -2) {
    *why = "the INI file's [STIFFPATH] value is longer than 767 characters";
    return -1;
  }
  if (found != 0 || !value[0]) {
    *why = "the INI file has no [STIFFPATH] value for it";
    return -1;
  }
  const char *slash = strrchr(ini, '/');
  if (value[0] != '/' && slash) {
    const int written = snprintf(out, size, "%.*s/%s", (int)(slash - ini), ini, value);
    if (written < 0 || (size_t)written >= size) {
      *why = "the file's path is too long";
      return -1;
    }
    if (strchr(value, '/') || access(out, F_OK) == 0) return 0;
  }
  if (strlen(value) + 1 > size) {
    *why = "the value is too long";
    return -1;
  }
  strcpy(out, value);
  return 0;
}

#endif
