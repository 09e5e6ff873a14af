// placeholder, replaced by the command-line program
int main() { return 0; }
