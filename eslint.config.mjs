// ESLint for the editor's page scripts (app/edit/web/): ES modules that run in the browser (the
// page's import map resolves 'three' and 'yaml'; tests/tools/ imports some of them in node).
// scripts/check-format.sh runs it as part of the format_check test.
import js from '@eslint/js';
import globals from 'globals';

export default [
  {
    files: ['app/edit/web/**/*.js'],
    ...js.configs.recommended,
    languageOptions: {
      ecmaVersion: 'latest',
      sourceType: 'module',
      globals: globals.browser,
    },
  },
];
