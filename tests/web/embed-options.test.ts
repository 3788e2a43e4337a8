// The embed's own options (web/src/embed/options.ts): theme, offline, and what stays out of the link.
import { describe, expect, it } from 'vitest';
import { linkParams, offlineAsked, theme, viewQuery } from '../../web/src/embed/options';

describe('embed options', () => {
  it('reads the theme, falling back to auto', () => {
    expect(theme([['theme', 'light']])).toBe('light');
    expect(theme([['theme', ' Dark ']])).toBe('dark');
    expect(theme([['theme', 'sepia']])).toBe('auto');
    expect(theme([])).toBe('auto');
  });
  it('asks for offline use only when told', () => {
    expect(offlineAsked([])).toBe(false);
    expect(offlineAsked([['offline', '']])).toBe(true);
    expect(offlineAsked([['offline', '1']])).toBe(true);
    expect(offlineAsked([['offline', '0']])).toBe(false);
  });
  it('keeps theme and offline out of the link state but in the page URL', () => {
    const params: [string, string][] = [['model', 'wat-rnn'], ['theme', 'dark'], ['offline', '1'], ['k', '5']];
    expect(linkParams(params)).toEqual([['model', 'wat-rnn'], ['k', '5']]);
    expect(viewQuery('?model=wat-rnn&theme=dark&offline=1&controls=full')).toEqual([['theme', 'dark'], ['offline', '1'], ['controls', 'full']]);
  });
});
