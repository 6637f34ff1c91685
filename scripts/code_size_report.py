#!/usr/bin/env python3
# Reports the headers above a line limit and the functions above a length limit in include/ (issue 13:
# no header above 600 lines, no function above 120 lines without a written reason). A function body is a
# line holding only '{' (the brace style of this project for functions) after a line ending in ')',
# 'const', 'override' or a trailing return type, up to its matching '}'. A reason is a comment line
# "// size: <why>" in the 5 lines above the function's signature or at the top of the file.
# Usage: scripts/code_size_report.py [include_dir] [--header-limit 600] [--function-limit 120]
import os, re, sys

def main():
    args = sys.argv[1:]
    root = 'include'
    header_limit, function_limit = 600, 120
    i = 0
    while i < len(args):
        if args[i] == '--header-limit': header_limit = int(args[i + 1]); i += 2
        elif args[i] == '--function-limit': function_limit = int(args[i + 1]); i += 2
        else: root = args[i]; i += 1
    over = 0
    for dirpath, _, files in os.walk(root):
        for name in sorted(files):
            if not name.endswith('.h'): continue
            path = os.path.join(dirpath, name)
            lines = open(path, encoding='utf-8', errors='replace').read().split('\n')
            file_reason = any(l.strip().startswith('// size:') for l in lines[:15])
            if len(lines) > header_limit and not file_reason:
                print('%s: %d lines (limit %d)' % (path, len(lines), header_limit)); over += 1
            for k, line in enumerate(lines):
                if line.strip() != '{' or k == 0: continue
                prev = lines[k - 1].rstrip()
                if not re.search(r'(\)|const|override|noexcept|> *[A-Za-z_:<>,* ]+)\s*$', prev): continue
                if re.match(r'\s*(struct|class|namespace|enum|union)\b', prev) or prev.strip().endswith('='): continue
                depth, j = 0, k
                while j < len(lines):
                    depth += lines[j].count('{') - lines[j].count('}')
                    if depth == 0: break
                    j += 1
                length = j - k + 1
                if length <= function_limit: continue
                start = k - 1
                while start > 0 and lines[start - 1].strip() and not lines[start - 1].strip().startswith(('//', '*', '/*', '}')):
                    start -= 1
                reason = any('// size:' in l for l in lines[max(0, start - 5):k])
                if not reason:
                    print('%s:%d: function of %d lines (limit %d): %s' % (path, k, length, function_limit, prev.strip()[:80])); over += 1
    print('%d over the limits' % over)
    return 1 if over else 0

if __name__ == '__main__':
    sys.exit(main())
