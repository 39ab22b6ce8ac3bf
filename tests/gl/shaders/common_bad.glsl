// Included by include_bad.frag: an error on line 3.
float helper(float x) {
  return x * missing_symbol;
}
