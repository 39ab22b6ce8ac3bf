// Included by include_error.frag.
float helper() {
  return missing_value;
}
