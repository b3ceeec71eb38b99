// Starts `rmot lsp` (the command in the setting rmot.server.command) for .rmot files.
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const [command, ...args] = vscode.workspace.getConfiguration("rmot").get("server.command", ["rmot", "lsp"]);
  client = new LanguageClient("rmot", "rmot", { command, args }, { documentSelector: [{ language: "rmot" }] });
  context.subscriptions.push({ dispose: () => client && client.stop() });
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
