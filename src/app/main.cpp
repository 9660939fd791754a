// Entry point of the `glint` command line program.
int main() { return 0; }
