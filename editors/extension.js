// The VS Code extension: the TextMate grammar (package.json) for colours, and the language
// server `rulec lsp` for everything else, started through vscode-languageclient.
'use strict';
const vscode = require('vscode');
const { LanguageClient } = require('vscode-languageclient/node');

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration('tranche');
  const args = ['lsp'];
  const stdlib = config.get('stdlib');
  if (stdlib) args.push('--stdlib', stdlib);
  const serverOptions = { command: config.get('rulec.path') || 'rulec', args };
  const clientOptions = { documentSelector: [{ scheme: 'file', language: 'tranche-rules' }] };
  client = new LanguageClient('tranche-rules', 'Tranche rules', serverOptions, clientOptions);
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
