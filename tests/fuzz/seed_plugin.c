/* A minimal shared library: the seed of a plugin file the check accepts. */
int rgraph_fuzz_seed_value(int x) { return x * 3 + 1; }
