// keeps the problems library non-empty before any generator exists
