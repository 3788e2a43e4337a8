import { describe, expect, it } from 'vitest';
import { keyAction } from '../../web/src/ui/keys';

const body = { tagName: 'BODY' };

describe('keyboard mapping', () => {
  it('maps the playback keys', () => {
    expect(keyAction({ key: ' ' }, body)).toEqual({ kind: 'toggle' });
    expect(keyAction({ key: 'ArrowRight' }, body)).toEqual({ kind: 'step', frames: 1 });
    expect(keyAction({ key: 'ArrowLeft', shiftKey: true }, body)).toEqual({ kind: 'step', frames: -10 });
    expect(keyAction({ key: ']' }, body)).toEqual({ kind: 'speed', direction: 1 });
    expect(keyAction({ key: '[' }, body)).toEqual({ kind: 'speed', direction: -1 });
    expect(keyAction({ key: 'Home' }, body)).toEqual({ kind: 'first' });
    expect(keyAction({ key: 'End' }, null)).toEqual({ kind: 'last' });
    expect(keyAction({ key: 'L', shiftKey: true }, body)).toEqual({ kind: 'layout' });
    expect(keyAction({ key: 'x' }, body)).toBeNull();
  });

  it('leaves browser shortcuts alone', () => {
    expect(keyAction({ key: 'l', ctrlKey: true }, body)).toBeNull();
    expect(keyAction({ key: 'ArrowLeft', altKey: true }, body)).toBeNull();
  });

  it('ignores keys typed into text and number fields', () => {
    for (const type of ['text', 'number', 'search']) {
      expect(keyAction({ key: ' ' }, { tagName: 'INPUT', type })).toBeNull();
      expect(keyAction({ key: 'l' }, { tagName: 'INPUT', type })).toBeNull();
    }
    expect(keyAction({ key: 'ArrowRight' }, { tagName: 'TEXTAREA' })).toBeNull();
    expect(keyAction({ key: 'ArrowRight' }, { tagName: 'SELECT' })).toBeNull();
    expect(keyAction({ key: 'l' }, { tagName: 'DIV', isContentEditable: true })).toBeNull();
  });

  it('lets focused controls keep their own keys', () => {
    expect(keyAction({ key: ' ' }, { tagName: 'BUTTON' })).toBeNull();
    expect(keyAction({ key: 'ArrowRight' }, { tagName: 'BUTTON' })).toEqual({ kind: 'step', frames: 1 });
    expect(keyAction({ key: 'ArrowRight' }, { tagName: 'INPUT', type: 'range' })).toBeNull();
    expect(keyAction({ key: ' ' }, { tagName: 'INPUT', type: 'range' })).toEqual({ kind: 'toggle' });
    expect(keyAction({ key: 'ArrowDown' }, { tagName: 'INPUT', type: 'radio' })).toBeNull();
    expect(keyAction({ key: 'l' }, { tagName: 'INPUT', type: 'radio' })).toEqual({ kind: 'layout' });
  });
});
